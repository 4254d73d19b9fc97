#include "common/splines/spline_space.h"

#include <algorithm>

namespace ffriga {

PatchPoint SplineSpace::evaluate(const double* xi, int order) const {
  PatchBasis R;
  elementBasis(findElement(xi), xi, order, R);
  return pointFromTable(R.table, R.index.data(), controlPoints(), paramDim(), order);
}

TensorSpace::TensorSpace(NurbsPatch patch) : patch_(std::move(patch)) {
  for (int a = 0; a < patch_.paramDim(); ++a) spans_[a] = patch_.knots(a).elementSpans();
}

ElementBox TensorSpace::element(int e) const {
  ElementBox box;
  for (int a = 0; a < paramDim(); ++a) {
    const int ne = static_cast<int>(spans_[a].size());
    const int s = spans_[a][e % ne];
    e /= ne;
    box.lower[a] = patch_.knots(a)[s];
    box.upper[a] = patch_.knots(a)[s + 1];
  }
  return box;
}

int TensorSpace::findElement(const double* xi) const {
  int e = 0;
  for (int a = paramDim() - 1; a >= 0; --a) {
    const int s = patch_.knots(a).findSpan(xi[a]);
    const int local = static_cast<int>(std::lower_bound(spans_[a].begin(), spans_[a].end(), s) -
                                       spans_[a].begin());
    e = e * static_cast<int>(spans_[a].size()) + local;
  }
  return e;
}

void TensorSpace::elementBasis(int e, const double* xi, int order, PatchBasis& out) const {
  // The span of the element, not findSpan(xi): xi on the element's upper boundary must use
  // the element's own polynomial pieces.
  const int d = paramDim();
  int spans[3] = {0, 0, 0};
  for (int a = 0; a < d; ++a) {
    const int ne = static_cast<int>(spans_[a].size());
    spans[a] = spans_[a][e % ne];
    e /= ne;
  }
  patch_.rationalBasisOnSpans(spans, xi, order, out);
}

}  // namespace ffriga
