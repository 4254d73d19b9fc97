#include "runtime/output/result_writer.h"

#include <exception>

#include "common/base/error.h"
#include "runtime/output/result_rows.h"
#include "runtime/output/sensor_rows.h"

namespace ffriga {

ResultWriter::ResultWriter(const std::string& path, const OutputLayout& layout,
                           const std::string& created_by, const std::string& scene_yaml,
                           const FlushConfig& flush_config, const RestartRecord* resume)
    : layout_(layout),
      file_(std::make_unique<ResultFile>(path, resume != nullptr)),
      flush_(flush_config),
      last_flush_(std::chrono::steady_clock::now()) {
  if (!resume) {
    file_->setAttribute("format", std::string(kResultFormat));
    file_->setAttribute("format_version", static_cast<long>(kResultFormatVersion));
    file_->setAttribute("scene_yaml", scene_yaml);
  }
  file_->setAttribute("created_by", created_by);
  file_->setAttribute("status", std::string("running"));
  sinks_.push_back(std::make_unique<ResultRows>(*file_, layout));
  sinks_.push_back(std::make_unique<SensorRows>(*file_, layout));
  // The restart record: the state at the last row on disk, rewritten at every flush.
  // Rows after the record's (written after its last flush, if any) are dropped.
  if (resume) {
    rows_ = resume->rows;
    restart_time_ = resume->time;
    file_->truncate(rows_);
  }
  auto restart = std::make_unique<RestartRecordWriter>(*file_, layout.state_size, rows_);
  restart_ = restart.get();
  sinks_.push_back(std::move(restart));
  auto pressure = std::make_unique<PeakContactPressure>(*file_, layout);
  pressure_ = pressure.get();
  sinks_.push_back(std::move(pressure));
  try {
    flush();
  } catch (const ComputeError& e) {  // no room for even the first flush
    if (file_->writable()) file_->setAttribute("status", std::string("failed: ") + e.what());
    throw;
  }
}

ResultWriter::~ResultWriter() {
  try {
    close();
  } catch (...) {
    // Destructors must not throw; close() explicitly to see errors.
  }
}

void ResultWriter::enableFrames(const VisualisationFramesConfig& settings) {
  auto frames = std::make_unique<FrameWriter>(*file_, layout_, settings, restart_time_);
  frames_ = frames.get();
  sinks_.push_back(std::move(frames));
}

void ResultWriter::enablePeakStressLines(std::vector<std::optional<HertzPartner>> partners) {
  auto peaks = std::make_unique<PeakStressLines>(*file_, layout_, std::move(partners));
  if (peaks->empty()) return;
  peaks_ = peaks.get();
  sinks_.push_back(std::move(peaks));
}

void ResultWriter::recordPeak(double t, double force, const std::vector<BodySample>& bodies) {
  if (peaks_) peaks_->recordPeak(t, force, bodies);
}

void ResultWriter::recordPressurePeak(int c, double t, double force, const PressureSample& field) {
  if (pressure_) pressure_->recordPeak(c, t, force, field);
}

void ResultWriter::append(const OutputSample& sample) {
  FFRIGA_CHECK(file_->open(), "result file " << file_->path() << " is closed");
  for (auto& sink : sinks_) sink->write(sample);
  ++rows_;
  if (rows_ % flush_.rows == 0)
    flush();
  else
    flushIfDue();
}

void ResultWriter::flushIfDue() {
  if (rows_ == file_->rowsWritten()) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_flush_).count() >= flush_.interval) flush();
}

void ResultWriter::flush() {
  if (!file_->writable() || refused_) return;
  std::uint64_t more = 0;
  for (const auto& sink : sinks_) more += sink->pendingBytes();
  try {
    file_->reserve(more);
  } catch (const ComputeError&) {
    refused_ = true;  // nothing was written: the file is as the last flush left it
    throw;
  }
  try {
    file_->writeRows(rows_);
    for (auto& sink : sinks_) sink->flush();
    file_->flushFile();
  } catch (...) {
    file_->markBroken();
    throw;
  }
  file_->measureGrowth();
  for (auto& sink : sinks_) sink->afterFlush();  // the XDMF file refers to frames on disk
  last_flush_ = std::chrono::steady_clock::now();
}

void ResultWriter::startSwmr() {
  flush();
  file_->startSwmr();
}

void ResultWriter::close() {
  if (!file_->open()) return;
  // The record again with the run's final figures: a flush by wall time right after the
  // last row wrote the figures of the step before, and whether one happened depends on the
  // machine's speed (same input, same bits).
  restart_->markPending();
  std::exception_ptr failure;
  if (file_->writable() && !refused_) {
    try {
      flush();
    } catch (const std::exception& e) {
      failure = std::current_exception();
      if (file_->writable()) file_->setAttribute("status", std::string("failed: ") + e.what());
    }
  }
  if (frames_) frames_written_ = frames_->frames();
  if (peaks_) peak_list_ = peaks_->peaks();
  frames_ = nullptr, peaks_ = nullptr, restart_ = nullptr, pressure_ = nullptr;
  if (file_->writable()) {
    for (auto& sink : sinks_) sink->finish();
  } else {
    for (auto& sink : sinks_) sink->abandon();
  }
  sinks_.clear();  // their datasets before the file
  file_->close();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace ffriga
