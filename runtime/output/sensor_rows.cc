#include "runtime/output/sensor_rows.h"

namespace ffriga {

SensorRows::SensorRows(ResultFile& file, const OutputLayout& layout) {
  if (layout.sensors.empty()) return;
  h5::Handle sensors = file.group(file.id(), "sensors");
  for (const SensorLayout& sensor : layout.sensors) {
    h5::Handle g = file.group(sensors.id(), sensor.name);
    h5::writeAttribute(file.context(), g.id(), "marker", sensor.marker);
    Series s;
    s.position = &file.series(g.id(), "position", 3, "m", "marker position, inertial");
    s.velocity = &file.series(g.id(), "velocity", 3, "m/s", "marker velocity, inertial");
    sensors_.push_back(s);
  }
}

void SensorRows::write(const OutputSample& sample) {
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    sensors_[i].position->append(sample.sensors[i].position.data());
    sensors_[i].velocity->append(sample.sensors[i].velocity.data());
  }
}

}  // namespace ffriga
