#include "measure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <numeric>
#include <sstream>
#include <utility>

#include "mddual/query.h"

namespace mddual::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Times one call (see measure.h); `convert` turns its result into an Answer
/// outside the timed region.
template <class Call, class Convert>
void timeOne(const Query& q, Call&& call, Convert&& convert, double overhead_ns, double* ns, Answer* answer) {
  try {
    const Clock::time_point t0 = Clock::now();
    const auto result = call(q);
    const Clock::time_point t1 = Clock::now();
    *ns = std::max(0.0, std::chrono::duration<double, std::nano>(t1 - t0).count() - overhead_ns);
    *answer = convert(result);
  } catch (const std::exception& e) {
    *ns = kNaN;
    *answer = Answer();
    answer->error = true;
    answer->message = e.what();
  }
}

void copyStats(const SearchStats& st, Answer* a) {
  a->centre_iterations = st.centre_iterations;
  a->steps = st.steps;
  a->rays = st.rays;
  a->support_vertices = st.support_vertices;
}

Answer fromMdd(const MddResult& r) {
  Answer a;
  a.contact = r.status != ContactStatus::kNoContact;
  a.value = r.distance;
  a.faces = r.stats.totalFaces();
  a.ee_faces = r.stats.ee_edge_faces;
  copyStats(r.stats, &a);
  return a;
}

Answer fromToi(const ToiResult& r) {
  Answer a;
  a.value = r.status == ToiStatus::kNever ? kInf : r.toi;
  a.contact = r.status != ToiStatus::kNever;
  a.faces = r.stats.totalFaces();
  a.ee_faces = r.stats.ee_edge_faces;
  copyStats(r.stats, &a);
  return a;
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

}  // namespace

double timerOverheadNs() {
  std::vector<double> samples(20001);
  for (double& s : samples) {
    const Clock::time_point t0 = Clock::now();
    const Clock::time_point t1 = Clock::now();
    s = std::chrono::duration<double, std::nano>(t1 - t0).count();
  }
  return percentile(samples, 50.0);
}

/// Stores one pass's measurement of query i: the answer of the first pass,
/// the fastest time over all passes.
void keep(int pass, size_t i, double ns, Answer&& answer, MethodRun* run) {
  if (pass == 0) {
    run->ns[i] = ns;
    run->answers[i] = std::move(answer);
  } else if (!(run->ns[i] <= ns)) {
    run->ns[i] = ns;
  }
}

MethodRun runOurs(const PairScene& s, bool mdd, bool warm, int passes, double overhead_ns) {
  MethodRun run;
  run.name = std::string(mdd ? "mdd" : "toi") + (warm ? "_warm" : "_cold");
  run.ours = true;
  run.is_mdd = mdd;
  run.warm = warm;
  const std::vector<Query>& qs = warm ? s.warm : s.cold;
  run.ns.resize(qs.size());
  run.answers.resize(qs.size());
  WarmStart cache;
  WarmStart* ws = warm ? &cache : nullptr;
  auto call_mdd = [&](const Query& q) { return mddual::mdd({&s.a, q.X_WA, &s.b, q.X_WB, q.s_W}, ws); };
  auto call_toi = [&](const Query& q) { return mddual::toi({&s.a, q.X_WA, &s.b, q.X_WB, q.s_W}, ws); };
  const size_t D = static_cast<size_t>(s.protocol.directions);
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t i = 0; i < qs.size(); ++i) {
      if (warm && i % D == 0) {
        // New sequence: a fresh cache, filled by the (untimed) primer query.
        cache = WarmStart();
        try {
          if (mdd) {
            call_mdd(s.primers[i / D]);
          } else {
            call_toi(s.primers[i / D]);
          }
        } catch (const std::exception&) {
          cache = WarmStart();
        }
      }
      double ns = kNaN;
      Answer answer;
      if (mdd) {
        timeOne(qs[i], call_mdd, fromMdd, overhead_ns, &ns, &answer);
      } else {
        timeOne(qs[i], call_toi, fromToi, overhead_ns, &ns, &answer);
      }
      keep(pass, i, ns, std::move(answer), &run);
    }
  }
  return run;
}

MethodRun runPeer(const PairScene& s, ToiPeer& peer, int passes, double overhead_ns) {
  MethodRun run;
  run.name = peer.name();
  run.ns.resize(s.cold.size());
  run.answers.resize(s.cold.size());
  auto call = [&](const Query& q) { return peer.toi(q); };
  auto convert = [](double t) {
    Answer a;
    a.value = t;
    a.contact = !(t == kInf);
    return a;
  };
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t i = 0; i < s.cold.size(); ++i) {
      double ns = kNaN;
      Answer answer;
      timeOne(s.cold[i], call, convert, overhead_ns, &ns, &answer);
      keep(pass, i, ns, std::move(answer), &run);
    }
  }
  return run;
}

double percentile(std::vector<double> values, double p) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double x) { return !std::isfinite(x); }), values.end());
  if (values.empty()) return kNaN;
  std::sort(values.begin(), values.end());
  const double pos = p / 100.0 * static_cast<double>(values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (pos - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

Summary summarize(const PairScene& s, const MethodRun& run, int max_examples) {
  const std::vector<Query>& qs = run.warm ? s.warm : s.cold;
  const std::vector<Reference>& refs = run.warm ? s.warm_ref : s.cold_ref;
  Summary out;
  out.queries = static_cast<int>(qs.size());
  std::vector<double> us;
  std::vector<double> separated_us;
  std::vector<double> in_contact_us;
  for (size_t i = 0; i < qs.size(); ++i) {
    us.push_back(run.ns[i] * 1e-3);
    (refs[i].in_contact ? in_contact_us : separated_us).push_back(run.ns[i] * 1e-3);
  }
  out.in_contact_median_us = percentile(in_contact_us, 50.0);
  out.in_contact_p90_us = percentile(in_contact_us, 90.0);
  out.median_us = percentile(us, 50.0);
  out.p90_us = percentile(us, 90.0);
  out.p99_us = percentile(us, 99.0);
  out.max_us = percentile(us, 100.0);
  out.separated_queries = static_cast<int>(separated_us.size());
  out.separated_median_us = percentile(separated_us, 50.0);
  out.separated_p90_us = percentile(separated_us, 90.0);
  double sum = 0.0;
  int timed = 0;
  for (double u : us) {
    if (std::isfinite(u)) {
      sum += u;
      ++timed;
    }
  }
  out.mean_us = timed > 0 ? sum / timed : kNaN;

  std::vector<double> errs;
  double faces_pct = 0.0, ee_pct = 0.0, faces_sum = 0.0, ee_sum = 0.0;
  double centre_sum = 0.0, steps_sum = 0.0, rays_sum = 0.0, support_sum = 0.0;
  int stat_queries = 0;
  const double exact = kExactRelTol * kSceneScale;
  for (size_t i = 0; i < qs.size(); ++i) {
    const Answer& a = run.answers[i];
    const Reference& r = refs[i];
    std::string problem;
    bool mismatch = false;
    if (a.error) {
      ++out.exceptions;
      problem = "exception: " + a.message;
    } else if (std::isnan(a.value) && (!run.is_mdd || a.contact)) {
      ++out.nans;
      problem = "NaN answer";
    } else {
      const bool ref_contact = run.is_mdd ? r.hit : std::isfinite(r.toi);
      const double ref_value = run.is_mdd ? r.mdd : r.toi;
      if (a.contact != ref_contact) {
        mismatch = true;
        if (r.ambiguous && !run.is_mdd) {
          ++out.ambiguous_accepted;
          if (run.ours) problem = "touching contact: answer " + fmt(a.value) + ", reference " + fmt(ref_value);
        } else if (ref_contact) {
          ++out.false_never;
          if (!run.is_mdd && r.in_contact && !r.overlapping) ++out.touch_never;
          problem = "reports no contact, reference " + fmt(ref_value);
        } else {
          ++out.false_hit;
          problem = "reports " + fmt(a.value) + ", reference: no contact";
        }
      } else if (a.contact && (run.is_mdd || a.value != 0.0 || ref_value != 0.0)) {
        const double err = std::abs(a.value - ref_value);
        errs.push_back(err / kSceneScale);
        if (err > exact) {
          mismatch = true;
          ++out.inexact;
          if (run.ours) problem = "answer " + fmt(a.value) + ", reference " + fmt(ref_value);
        }
        if (err > kLargeErrRel * kSceneScale) {
          ++out.large_err;
          problem = "answer " + fmt(a.value) + ", reference " + fmt(ref_value) + " (error " + fmt(err) + ")";
        }
      }
      if (!run.is_mdd && r.overlapping) {
        ++out.overlap_queries;
        if (!a.contact) {
          ++out.overlap_never;
        } else if (a.value <= exact) {
          ++out.overlap_zero;
        } else {
          ++out.overlap_positive;
        }
      }
    }
    if (run.ours && (mismatch || a.error || !problem.empty())) ++out.mismatches;
    // Examples: the first failures, but at most one of the (many, alike)
    // overlapping starts that a peer reports as "never".
    const bool overlap_never = !run.is_mdd && r.overlapping && !a.contact && !a.error;
    if (!problem.empty() && static_cast<int>(out.examples.size()) < max_examples &&
        (!overlap_never || out.overlap_never == 1)) {
      out.examples.push_back(
          run.name + " query " + std::to_string(i) + " (orientation " + std::to_string(qs[i].orientation) + ", delta " +
          fmt(s.deltas[static_cast<size_t>(qs[i].placement)]) + "): " + problem + "\n  " + describeQuery(s, qs[i]));
    }
    if (run.ours && r.hit && !a.error && a.faces >= 0) {
      const OrientationInfo& o = s.orientations[static_cast<size_t>(qs[i].orientation)];
      faces_pct += 100.0 * a.faces / o.faces;
      ee_pct += o.ee_faces > 0 ? 100.0 * a.ee_faces / o.ee_faces : 0.0;
      faces_sum += a.faces;
      ee_sum += a.ee_faces;
      centre_sum += a.centre_iterations;
      steps_sum += a.steps;
      rays_sum += a.rays;
      support_sum += a.support_vertices;
      ++stat_queries;
    }
  }
  out.failures = out.exceptions + out.nans + out.false_never + out.false_hit;
  out.compared = static_cast<int>(errs.size());
  if (!errs.empty()) {
    out.max_err = *std::max_element(errs.begin(), errs.end());
    out.median_err = percentile(errs, 50.0);
    out.mean_err = std::accumulate(errs.begin(), errs.end(), 0.0) / static_cast<double>(errs.size());
  }
  if (run.ours && stat_queries > 0) {
    const double n = stat_queries;
    out.faces_visited_pct = faces_pct / n;
    out.ee_faces_visited_pct = ee_pct / n;
    out.faces_visited_mean = faces_sum / n;
    out.ee_faces_visited_mean = ee_sum / n;
    out.centre_iterations_mean = centre_sum / n;
    out.steps_mean = steps_sum / n;
    out.rays_mean = rays_sum / n;
    out.support_vertices_mean = support_sum / n;
  }
  return out;
}

}  // namespace mddual::bench
