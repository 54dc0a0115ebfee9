#include "qhull_wrapper.h"

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "mddual/error.h"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace mddual::detail {
namespace {

/// Captures what qhull writes to its error stream, so that our exception can
/// carry qhull's own explanation.
class ErrorCapture {
 public:
  ErrorCapture() : stream_(open_memstream(&buffer_, &size_)) {}
  ~ErrorCapture() {
    if (stream_ != nullptr) std::fclose(stream_);
    std::free(buffer_);
  }
  ErrorCapture(const ErrorCapture&) = delete;
  ErrorCapture& operator=(const ErrorCapture&) = delete;

  FILE* stream() const { return stream_; }
  std::string text() {
    if (stream_ == nullptr) return "(qhull message unavailable)";
    std::fflush(stream_);
    std::string s(buffer_ != nullptr ? buffer_ : "", size_);
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    return s;
  }

 private:
  char* buffer_ = nullptr;
  size_t size_ = 0;
  FILE* stream_ = nullptr;
};

/// qhull's diagnostic, cut to its first sentence: qhull prints kilobytes of
/// options, statistics and advice after it, which must not reach a user's
/// error message raw. "QH6214 qhull input error: not enough points(3) to
/// construct initial simplex (need 4)\n..." becomes "QH6214 qhull input
/// error: not enough points(3) to construct initial simplex (need 4)".
std::string summary(const std::string& text) {
  constexpr std::size_t kMaxChars = 200;
  std::size_t start = text.find("QH");
  if (start == std::string::npos) start = 0;
  std::string line = text.substr(start, text.find('\n', start) - start);
  const std::size_t stop = line.find(". ");
  if (stop != std::string::npos) line.resize(stop);
  if (line.size() > kMaxChars) line = line.substr(0, kMaxChars) + "...";
  return line.empty() ? std::string("(no message from qhull)") : line;
}

/// Owns one qhull run: constructs, runs and frees it.
class QhullRun {
 public:
  QhullRun(int dim, std::vector<coordT>* coords, const std::string& what, double premerge = 0.0) {
    qh_zero(&qh_, errors_.stream());
    // Default "qhull" pre-merges coplanar facets within round-off (C-0);
    // "C-n" widens that to centrums within n of a neighbour's plane.
    std::string text = "qhull";
    if (premerge > 0.0) {
      char value[64];
      std::snprintf(value, sizeof(value), " C-%.3g", premerge);
      text += value;
    }
    std::vector<char> options(text.begin(), text.end());
    options.push_back('\0');
    const int count = static_cast<int>(coords->size()) / dim;
    exit_code_ = qh_new_qhull(&qh_, dim, count, coords->data(), False, options.data(), nullptr, errors_.stream());
    if (exit_code_ != 0) {
      // The destructor does not run when the constructor throws: free here
      // (qhull allocated its buffers before it failed; the fuzzer's leak
      // check found them lost on every failed hull).
      const std::string message = summary(errors_.text());
      release();
      throw HullError(what + ": the convex hull failed (qhull exit code " + std::to_string(exit_code_) +
                      "): " + message);
    }
  }
  ~QhullRun() { release(); }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  qhT* qh() { return &qh_; }

 private:
  void release() {
    if (released_) return;
    released_ = true;
    qh_freeqhull(&qh_, !qh_ALL);
    int curlong = 0;
    int totlong = 0;
    qh_memfreeshort(&qh_, &curlong, &totlong);
  }

  bool released_ = false;
  qhT qh_{};
  ErrorCapture errors_;
  int exit_code_ = 0;
};

}  // namespace

std::vector<HullFacet> hull3d(const std::vector<Eigen::Vector3d>& points, const std::string& what, double premerge) {
  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  for (const Eigen::Vector3d& p : points) {
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  }
  QhullRun run(3, &coords, what, premerge);
  qhT* qh = run.qh();

  std::vector<HullFacet> facets;
  facetT* facet = nullptr;
  FORALLfacets {
    HullFacet out;
    out.normal = Eigen::Vector3d(facet->normal[0], facet->normal[1], facet->normal[2]);
    out.offset = -facet->offset;  // qhull: normal . x + offset = 0
    setT* ordered = qh_facet3vertex(qh, facet);
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FOREACHvertex_(ordered) {
      out.vertices.push_back(qh_pointid(qh, vertex->point));
    }
    qh_settempfree(qh, &ordered);
    // Orient counter-clockwise about the outward normal (Newell's normal).
    Eigen::Vector3d newell = Eigen::Vector3d::Zero();
    const int k = static_cast<int>(out.vertices.size());
    for (int i = 0; i < k; ++i) {
      newell += points[out.vertices[i]].cross(points[out.vertices[(i + 1) % k]]);
    }
    if (newell.dot(out.normal) < 0.0) std::reverse(out.vertices.begin(), out.vertices.end());
    facets.push_back(std::move(out));
  }
  return facets;
}

std::vector<int> hull2d(const std::vector<Eigen::Vector2d>& points, const std::string& what) {
  std::vector<coordT> coords;
  coords.reserve(points.size() * 2);
  for (const Eigen::Vector2d& p : points) coords.insert(coords.end(), {p.x(), p.y()});
  QhullRun run(2, &coords, what);
  qhT* qh = run.qh();

  // In 2D every facet is an edge with two vertices; walk facet neighbours.
  // qhull's toporient flag tells which of the two vertices comes first going
  // counter-clockwise; we instead order by a cross-product test below.
  std::vector<int> ring;
  facetT* start = qh->facet_list;
  facetT* facet = start;
  vertexT* prev = nullptr;
  do {
    vertexT* a = static_cast<vertexT*>(facet->vertices->e[0].p);
    vertexT* b = static_cast<vertexT*>(facet->vertices->e[1].p);
    vertexT* next = (prev == nullptr || a == prev) ? b : a;
    vertexT* here = (next == b) ? a : b;
    ring.push_back(qh_pointid(qh, here->point));
    // The neighbour facet that contains `next`.
    facetT* n0 = static_cast<facetT*>(facet->neighbors->e[0].p);
    facetT* n1 = static_cast<facetT*>(facet->neighbors->e[1].p);
    const bool n0_has =
        static_cast<vertexT*>(n0->vertices->e[0].p) == next || static_cast<vertexT*>(n0->vertices->e[1].p) == next;
    prev = next;
    facet = n0_has ? n0 : n1;
  } while (facet != start && ring.size() <= points.size());

  double area2 = 0.0;
  const int k = static_cast<int>(ring.size());
  for (int i = 0; i < k; ++i) {
    const Eigen::Vector2d& p = points[ring[i]];
    const Eigen::Vector2d& q = points[ring[(i + 1) % k]];
    area2 += p.x() * q.y() - p.y() * q.x();
  }
  if (area2 < 0.0) std::reverse(ring.begin(), ring.end());
  return ring;
}

}  // namespace mddual::detail
