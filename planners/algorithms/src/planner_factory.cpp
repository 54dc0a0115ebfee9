#include "mddual/planning/planner_factory.h"

#include <ompl/geometric/planners/AnytimePathShortening.h>
#include <ompl/geometric/planners/cforest/CForest.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/prm/SPARS.h>
#include <ompl/geometric/planners/prm/SPARStwo.h>
#include <ompl/geometric/planners/rlrt/BiRLRT.h>
#include <ompl/geometric/planners/rlrt/RLRT.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTXstatic.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/rrt/pRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sbl/pSBL.h>
#include <ompl/geometric/planners/sst/SST.h>
#include <ompl/geometric/planners/stride/STRIDE.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <type_traits>

#include "mddual/error.h"
#include "mddual/planning/exact_rrt_connect.h"

namespace mddual::planning {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Allocator = std::function<ob::PlannerPtr(const ob::SpaceInformationPtr&)>;

template <class P>
Allocator make() {
  return [](const ob::SpaceInformationPtr& si) { return std::make_shared<P>(si); };
}

/// OMPL.app's names for its geometric planners (ompl_benchmark's list, plus
/// OMPL 1.5's informed planners, the same set mddual::scene::knownPlannerNames
/// accepts in a config), the other geometric planners of OMPL 1.5 that need
/// nothing but the space information, and ours. Not here: TSRRT, VFRRT,
/// XXL, QRRT and the experience planners (Lightning, Thunder), which need a
/// task space, a vector field, a decomposition, a hierarchy of spaces or a
/// path database, and LazyLBTRRT, which aborts the process on an assertion
/// inside OMPL 1.5.2 (LPAstarOnGraph::removeEdge) on a small SE(2) problem.
const std::map<std::string, Allocator>& registry() {
  static const std::map<std::string, Allocator> planners{
      {"abitstar", make<og::ABITstar>()},
      {"aitstar", make<og::AITstar>()},
      {"aps", make<og::AnytimePathShortening>()},
      {"bfmt", make<og::BFMT>()},
      {"biest", make<og::BiEST>()},
      {"birlrt", make<og::BiRLRT>()},
      {"bitrrt", make<og::BiTRRT>()},
      {"bitstar", make<og::BITstar>()},
      {"bkpiece", make<og::BKPIECE1>()},
      {"cforest", make<og::CForest>()},
      {"est", make<og::EST>()},
      {"fmt", make<og::FMT>()},
      {"informedrrtstar", make<og::InformedRRTstar>()},
      {"kpiece", make<og::KPIECE1>()},
      {"lazyprm", make<og::LazyPRM>()},
      {"lazyprmstar", make<og::LazyPRMstar>()},
      {"lazyrrt", make<og::LazyRRT>()},
      {"lbkpiece", make<og::LBKPIECE1>()},
      {"lbtrrt", make<og::LBTRRT>()},
      {"pdst", make<og::PDST>()},
      {"prm", make<og::PRM>()},
      {"prmstar", make<og::PRMstar>()},
      {"projest", make<og::ProjEST>()},
      {"prrt", make<og::pRRT>()},
      {"psbl", make<og::pSBL>()},
      {"rlrt", make<og::RLRT>()},
      {"rrt", make<og::RRT>()},
      {"rrtconnect", make<og::RRTConnect>()},
      {"rrtsharp", make<og::RRTsharp>()},
      {"rrtstar", make<og::RRTstar>()},
      {"rrtxstatic", make<og::RRTXstatic>()},
      {"sbl", make<og::SBL>()},
      {"sorrtstar", make<og::SORRTstar>()},
      {"spars", make<og::SPARS>()},
      {"spars2", make<og::SPARStwo>()},
      {"sst", make<og::SST>()},
      {"stride", make<og::STRIDE>()},
      {"trrt", make<og::TRRT>()},
      // ours
      {kExactRRTConnectName, make<ExactRRTConnect>()},
  };
  return planners;
}

/// Other spellings: OMPL's own planner names (Planner::getName(), lower
/// case) where they differ from OMPL.app's.
const std::map<std::string, std::string>& aliases() {
  static const std::map<std::string, std::string> names{
      {"anytimepathshortening", "aps"}, {"bkpiece1", "bkpiece"}, {"kpiece1", "kpiece"},
      {"lbkpiece1", "lbkpiece"},        {"rrt#", "rrtsharp"},    {"sparstwo", "spars2"},
  };
  return names;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string knownList() {
  std::string known;
  for (const std::string& n : plannerNames()) known += (known.empty() ? "" : ", ") + n;
  return known;
}

/// OMPL's range suggestion "low:step:high" or "low:high" as (low, high)
/// texts; false when it has no such form (a boolean's "0,1", a string's "").
bool rangeSuggestion(const ob::GenericParam& param, std::string* low, std::string* high) {
  const std::string& range = param.getRangeSuggestion();
  const std::size_t first = range.find(':');
  if (first == std::string::npos) return false;
  *low = range.substr(0, first);
  *high = range.substr(range.rfind(':') + 1);
  return true;
}

/// A value outside the range OMPL declares gets a warning (a range
/// suggestion, not always a limit: a planner's range may exceed 10000 in a
/// large world, a goal bias of 5 makes no sense).
void warnOutsideRange(const ob::GenericParam& param, double v, const std::string& where) {
  std::string low, high;
  if (!rangeSuggestion(param, &low, &high)) return;
  if (v < std::strtod(low.c_str(), nullptr) || v > std::strtod(high.c_str(), nullptr)) {
    OMPL_WARN("%s: outside the range OMPL declares for it, [%s, %s]", where.c_str(), low.c_str(), high.c_str());
  }
}

/// Integer parameters below which OMPL 1.5.2 crashes or aborts, by planner
/// (canonical name) and parameter: APS with no planners (segmentation fault),
/// STRIDE's GNAT of degree 0 (an Eigen assertion; also a minimum degree of 0
/// in a benchmark run), pSBL's and pRRT's thread counts of 0 and AIT*'s
/// batches of no samples (OMPL's assertions). Found by a hostile-input hunt
/// (`mddual bench` on thin_walls), each confirmed alone on a small SE(3)
/// problem; CForest with no threads, BIT*'s and FMT*'s zero samples and
/// STRIDE's other degrees ran there. Smaller values are refused.
std::uint64_t hardMinimum(const std::string& planner, const std::string& key) {
  static const std::map<std::pair<std::string, std::string>, std::uint64_t> minimums{
      {{"aps", "num_planners"}, 1},  {{"stride", "degree"}, 1},     {{"stride", "min_degree"}, 1},
      {{"psbl", "thread_count"}, 1}, {{"prrt", "thread_count"}, 1}, {{"aitstar", "samples_per_batch"}, 1},
  };
  const auto it = minimums.find({planner, key});
  return it == minimums.end() ? 0 : it->second;
}

/// An integer parameter's value: decimal digits after an optional sign, within
/// the parameter's type (OMPL's conversion turned -1 into 4294967295, 2.5
/// into 2 and 1e300 into 1; "-0" is 0) and not below hardMinimum. Returns the
/// value without a '+' (for OMPL's conversion).
template <class T>
std::string checkInteger(const ob::GenericParam& param, const std::string& value, const std::string& planner,
                         const std::string& key, const std::string& where) {
  const bool sign = !value.empty() && (value[0] == '+' || value[0] == '-');
  const bool negative = sign && value[0] == '-';
  const std::string digits = sign ? value.substr(1) : value;
  const bool all_digits = !digits.empty() && std::all_of(digits.begin(), digits.end(),
                                                         [](unsigned char c) { return std::isdigit(c) != 0; });
  if (!all_digits) throw InvalidInputError(where + ": not an integer");
  const bool zero = digits.find_first_not_of('0') == std::string::npos;
  if (negative && !zero && !std::is_signed<T>::value) throw InvalidInputError(where + ": must be 0 or more");
  // from_chars: exact for the type (no long double in between), a '-' only.
  const std::string text = negative && !zero ? "-" + digits : digits;
  T v{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw InvalidInputError(where + ": out of range (" + std::to_string(std::numeric_limits<T>::min()) + " to " +
                            std::to_string(std::numeric_limits<T>::max()) + ")");
  }
  const std::uint64_t minimum = hardMinimum(planner, key);
  bool below = false;
  if constexpr (std::is_signed<T>::value) below = v < 0;
  if (minimum > 0 && (below || static_cast<std::uint64_t>(v) < minimum)) {
    throw InvalidInputError(where + ": must be at least " + std::to_string(minimum) +
                            " (OMPL's planner fails below it)");
  }
  warnOutsideRange(param, static_cast<double>(v), where);
  return text;
}

/// Checks `value` for the parameter's type and returns it as OMPL's setParam
/// wants it: a real must be a finite number (OMPL would store NaN, or fail
/// with a message that names neither), an integer as checkInteger says, a
/// boolean one of true/false, t/f, 1/0, yes/no, on/off in any case, passed
/// on as "1" or "0" (OMPL's conversion read every text but "", "0", "false"
/// and "f" in their usual cases as true: "no", "off", "abc"). Other types
/// (APS's list of planners, checked by checkApsPlanners) pass unchanged.
std::string checkedValue(const ob::GenericParam& param, const std::string& value, const std::string& planner,
                         const std::string& key, const std::string& where) {
  if (dynamic_cast<const ob::SpecificParam<double>*>(&param) != nullptr) {
    char* end = nullptr;
    const double v = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(v)) {
      throw InvalidInputError(where + ": not a finite number");
    }
    warnOutsideRange(param, v, where);
  } else if (dynamic_cast<const ob::SpecificParam<bool>*>(&param) != nullptr) {
    const std::string v = lower(value);
    if (v == "1" || v == "true" || v == "t" || v == "yes" || v == "on") return "1";
    if (v == "0" || v == "false" || v == "f" || v == "no" || v == "off") return "0";
    throw InvalidInputError(where + ": not a boolean (true/false, t/f, 1/0, yes/no, on/off)");
  } else if (dynamic_cast<const ob::SpecificParam<int>*>(&param) != nullptr) {
    return checkInteger<int>(param, value, planner, key, where);
  } else if (dynamic_cast<const ob::SpecificParam<unsigned int>*>(&param) != nullptr) {
    return checkInteger<unsigned int>(param, value, planner, key, where);
  } else if (dynamic_cast<const ob::SpecificParam<unsigned long>*>(&param) != nullptr) {
    return checkInteger<unsigned long>(param, value, planner, key, where);
  } else if (dynamic_cast<const ob::SpecificParam<long>*>(&param) != nullptr) {
    return checkInteger<long>(param, value, planner, key, where);
  }
  return value;
}

/// APS's list of planners as OMPL 1.5.2 reads it ("RRTConnect,PRM[max_nearest_neighbors=8 range=1]"):
/// split at ',', each entry at '[', ' ' and ']', the first piece the planner's
/// class name (one of those below; not LazyLBTRRT, which aborts, see
/// registry()), the others key=value for it. OMPL logs an unknown name and goes
/// on without it, setting the parameters after it on the planner before it
/// (or indexing an empty list), and indexes past a piece without '=': so
/// every entry is checked here first, its parameters as makePlanner checks
/// them (on a planner made for the purpose). An empty list is OMPL's
/// default planners.
void checkApsPlanners(const std::string& value, const ob::SpaceInformationPtr& si, const std::string& where) {
  static const std::set<std::string> kApsNames = {
      "BFMT",        "BiEST",   "BiTRRT",     "BITstar", "BKPIECE", "EST",      "FMT",     "KPIECE",  "LazyPRM",
      "LazyPRMstar", "LazyRRT", "LBKPIECE",   "LBTRRT",  "PDST",    "PRM",      "PRMstar", "ProjEST", "RRT",
      "RRTConnect",  "RRTstar", "RRTXstatic", "SBL",     "SPARS",   "SPARStwo", "SST",     "STRIDE",  "TRRT"};
  if (value.empty()) return;
  const auto split = [](const std::string& text, const std::string& at) {
    std::vector<std::string> pieces(1);
    for (const char c : text) {
      if (at.find(c) != std::string::npos) {
        pieces.emplace_back();
      } else {
        pieces.back() += c;
      }
    }
    return pieces;
  };
  for (const std::string& entry : split(value, ",")) {
    const std::vector<std::string> pieces = split(entry, "[ ]");
    const std::string& name = pieces[0];
    if (kApsNames.count(name) == 0) {
      throw InvalidInputError(where + ": '" + clipForMessage(name) + "' in '" + clipForMessage(entry) +
                              "' is not a planner APS makes (OMPL's class names, e.g. RRTConnect,PRM; no spaces "
                              "around commas; parameters in brackets are separated by spaces)");
    }
    std::vector<std::pair<std::string, std::string>> params;
    for (std::size_t k = 1; k < pieces.size(); ++k) {
      if (pieces[k].empty()) continue;
      const std::size_t eq = pieces[k].find('=');
      if (eq == std::string::npos || eq == 0) {
        throw InvalidInputError(where + ": '" + clipForMessage(pieces[k]) + "' in '" + clipForMessage(entry) +
                                "' is not key=value");
      }
      params.emplace_back(pieces[k].substr(0, eq), pieces[k].substr(eq + 1));
    }
    try {
      makePlanner(canonicalPlannerName(name), si, params);
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(where + ": " + e.what());
    }
  }
}

/// A planner's display name: the name in the benchmark's log and table.
void checkPlannerName(const std::string& planner, const std::string& value) {
  const std::string where = "planner '" + planner + "': name '" + clipForMessage(value) + "'";
  if (value.empty()) throw InvalidInputError("planner '" + planner + "': name is empty");
  if (std::any_of(value.begin(), value.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f || c == '|'; })) {
    throw InvalidInputError(where + ": control characters and '|' are not allowed (the results table)");
  }
  const std::string other = canonicalPlannerName(value);
  if (!other.empty() && other != canonicalPlannerName(planner)) {
    throw InvalidInputError(where + " is the name of another planner, '" + other + "'");
  }
}

}  // namespace

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const auto& [name, alloc] : registry()) names.push_back(name);
  return names;
}

std::string canonicalPlannerName(const std::string& name) {
  std::string key = lower(name);
  const auto alias = aliases().find(key);
  if (alias != aliases().end()) key = alias->second;
  return registry().count(key) != 0 ? key : std::string();
}

ob::PlannerPtr makePlanner(const std::string& name, const ob::SpaceInformationPtr& si,
                           const std::vector<std::pair<std::string, std::string>>& params) {
  const auto it = registry().find(canonicalPlannerName(name));
  if (it == registry().end()) throw InvalidInputError("unknown planner '" + name + "' (known: " + knownList() + ")");
  ob::PlannerPtr planner = it->second(si);
  for (const auto& [key, value] : params) {
    if (key == "name") {
      checkPlannerName(name, value);
      planner->setName(value);
    } else if (!planner->params().hasParam(key)) {
      throw InvalidInputError("planner '" + name + "' has no parameter '" + key + "'");
    } else {
      const std::string where = "planner '" + name + "': parameter '" + key + "' = '" + clipForMessage(value) + "'";
      const std::string checked = checkedValue(*planner->params().getParams().at(key), value, it->first, key, where);
      if (it->first == "aps" && key == "planners") checkApsPlanners(value, si, where);
      bool ok = false;
      try {
        ok = planner->params().setParam(key, checked);
      } catch (const std::exception& e) {
        throw InvalidInputError(where + ": " + e.what());
      }
      if (!ok) throw InvalidInputError(where + ": OMPL rejects the value");
    }
  }
  return planner;
}

std::vector<scene::PlannerSpec> selectPlannerSpecs(const std::vector<scene::PlannerSpec>& listed,
                                                   const std::vector<std::string>& names, const std::string& cfg_name) {
  if (names.empty()) {
    if (listed.empty()) {
      throw InvalidInputError(cfg_name + ": the [planner] section names no planner (name some, or choose them with " +
                              "--planners)");
    }
    return listed;
  }
  // Each name: the cfg's instances of it (by its own spelling or OMPL.app's),
  // else a new instance with default parameters.
  std::vector<bool> take(listed.size(), false);
  std::vector<scene::PlannerSpec> defaults;
  for (const std::string& name : names) {
    const std::string canonical = canonicalPlannerName(name);
    bool found = false;
    for (std::size_t i = 0; i < listed.size(); ++i) {
      if (listed[i].name == name || (!canonical.empty() && listed[i].name == canonical)) {
        take[i] = true;
        found = true;
      }
    }
    if (found) continue;
    if (canonical.empty()) {
      std::string in_cfg;
      for (const scene::PlannerSpec& p : listed) {
        if (in_cfg.find(" " + p.name + ",") == std::string::npos) in_cfg += " " + p.name + ",";
      }
      in_cfg = in_cfg.empty() ? "none" : in_cfg.substr(1, in_cfg.size() - 2);
      throw InvalidInputError("unknown planner '" + name + "': not in " + cfg_name + " (its planners: " + in_cfg +
                              ") and not a planner name (known: " + knownList() + ")");
    }
    const bool twice =
        std::any_of(defaults.begin(), defaults.end(), [&](const scene::PlannerSpec& p) { return p.name == canonical; });
    if (twice) continue;
    scene::PlannerSpec spec;
    spec.name = canonical;
    defaults.push_back(spec);
  }
  std::vector<scene::PlannerSpec> out;
  for (std::size_t i = 0; i < listed.size(); ++i) {
    if (take[i]) out.push_back(listed[i]);
  }
  out.insert(out.end(), defaults.begin(), defaults.end());
  return out;
}

double discardedLastValidFraction(const ob::Planner& planner) {
  // KPIECE1, BKPIECE1 and STRIDE keep a failed extension, and LBKPIECE1
  // re-adds the valid part of a failed lazy edge, only when lastValid.second
  // > minValidPathFraction_ (OMPL 1.5's solve() and isPathValid()); a
  // smaller fraction is dropped whatever its exact value.
  if (const auto* p = dynamic_cast<const og::KPIECE1*>(&planner)) return p->getMinValidPathFraction();
  if (const auto* p = dynamic_cast<const og::BKPIECE1*>(&planner)) return p->getMinValidPathFraction();
  if (const auto* p = dynamic_cast<const og::LBKPIECE1*>(&planner)) return p->getMinValidPathFraction();
  if (const auto* p = dynamic_cast<const og::STRIDE*>(&planner)) return p->getMinValidPathFraction();
  return 0.0;
}

}  // namespace mddual::planning
