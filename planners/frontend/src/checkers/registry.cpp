// The checker tables (checker_registry.h): one line per checker, whose entry
// is defined in a file of its own in this folder; checkers of optional
// libraries append theirs with addRigidChecker / addArmChecker.
#include <sstream>

#include "mddual/error.h"
#include "mddual/planning/checker_registry.h"

namespace mddual::planning {

// Rigid bodies: mdd_checker.cpp, fcl_checker.cpp, fcl_continuous_checker.cpp.
RigidChecker mddChecker();
RigidChecker fclChecker();
RigidChecker fclContinuousChecker();

namespace {

std::vector<RigidChecker>& rigidTable() {
  static std::vector<RigidChecker> table{
      mddChecker(),
      fclChecker(),
      fclContinuousChecker(),
  };
  return table;
}

}  // namespace

const std::vector<RigidChecker>& rigidCheckers() {
  return rigidTable();
}

// Arms: arm_mdd_checker.cpp, arm_fcl_checker.cpp (fcl and fcl-fine).
ArmChecker armMddChecker();
ArmChecker armFclChecker();
ArmChecker armFclFineChecker();

namespace {

std::vector<ArmChecker>& armTable() {
  static std::vector<ArmChecker> table{
      armMddChecker(),
      armFclChecker(),
      armFclFineChecker(),
  };
  return table;
}

}  // namespace

const std::vector<ArmChecker>& armCheckers() {
  return armTable();
}

// ---- Names ----------------------------------------------------------------------------

namespace {

template <class Entry>
std::vector<std::string> entryNames(const std::vector<Entry>& table) {
  std::vector<std::string> names;
  for (const Entry& e : table) names.emplace_back(e.name);
  return names;
}

/// "mdd, fcl, fcl-continuous".
std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// The entry of `table` called `name`; `what` is "checker" or "arm checker".
template <class Entry>
const Entry& findEntry(const std::vector<Entry>& table, const std::string& name, const char* what) {
  for (const Entry& e : table) {
    if (name == e.name) return e;
  }
  throw InvalidInputError(std::string("unknown ") + what + " '" + clipForMessage(name) +
                          "' (known: " + joinNames(entryNames(table)) + ")");
}

/// Appends `entry` to `table`, or nothing when an entry of the same name and
/// install function is there already (a second registration call).
template <class Entry>
void addEntry(std::vector<Entry>& table, const Entry& entry, const char* what) {
  if (entry.name == nullptr || entry.description == nullptr || entry.install == nullptr) {
    throw InvalidInputError(std::string("add ") + what + ": the name, description and install function must be set");
  }
  const std::string name = entry.name;
  if (name.empty() || name.find(',') != std::string::npos) {
    throw InvalidInputError(std::string("add ") + what + ": bad name '" + clipForMessage(name) +
                            "' (empty or with a comma)");
  }
  for (const Entry& e : table) {
    if (name != e.name) continue;
    if (e.install == entry.install) return;
    throw InvalidInputError(std::string("add ") + what + ": the table has a checker named '" + name + "' already");
  }
  table.push_back(entry);
}

template <class Entry>
std::vector<std::string> parseNames(const std::vector<Entry>& table, const std::string& list, const char* what) {
  std::vector<std::string> names;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty()) throw InvalidInputError("empty checker name in '" + clipForMessage(list) + "'");
    findEntry(table, item, what);
    for (const std::string& seen : names) {
      if (seen == item) {
        throw InvalidInputError("checker '" + item + "' given twice in '" + clipForMessage(list) + "'");
      }
    }
    names.push_back(item);
  }
  if (names.empty() || (!list.empty() && list.back() == ',')) {
    throw InvalidInputError("no checker in '" + clipForMessage(list) + "' (known: " + joinNames(entryNames(table)) +
                            ")");
  }
  return names;
}

}  // namespace

std::vector<std::string> rigidCheckerNames() {
  return entryNames(rigidCheckers());
}

const RigidChecker& findRigidChecker(const std::string& name) {
  return findEntry(rigidCheckers(), name, "checker");
}

std::vector<std::string> parseCheckerList(const std::string& list) {
  return parseNames(rigidCheckers(), list, "checker");
}

void addRigidChecker(const RigidChecker& checker) {
  addEntry(rigidTable(), checker, "checker");
}

void addArmChecker(const ArmChecker& checker) {
  addEntry(armTable(), checker, "arm checker");
}

std::vector<std::string> armCheckerNames() {
  return entryNames(armCheckers());
}

const ArmChecker& findArmChecker(const std::string& name) {
  return findEntry(armCheckers(), name, "arm checker");
}

std::vector<std::string> parseArmCheckerList(const std::string& list) {
  return parseNames(armCheckers(), list, "arm checker");
}

}  // namespace mddual::planning
