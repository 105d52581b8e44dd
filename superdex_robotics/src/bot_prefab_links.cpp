// BotLinkPrefab: a link of a BotPrefab together with the sensors and actuators declared on it.

#include "superdex/physics/error.h"
#include "superdex/robotics/bot_prefab.h"

namespace superdex::robotics {
inline namespace SUPERDEX_REAL_NAMESPACE {

BotLinkPrefab link_prefab(const BotPrefab& prefab, int index) {
  const int n = static_cast<int>(prefab.articulation.links.size());
  if (index < 0 || index >= n)
    throw Error("link_prefab: index " + std::to_string(index) + " is out of range (" + std::to_string(n) + " links)");
  BotLinkPrefab out;
  static_cast<physics::LinkDesc&>(out) = prefab.articulation.links[index];
  if (index < static_cast<int>(prefab.sensors.size()))
    for (const ComponentDecl& d : prefab.sensors[index]) out.sensors.push_back({d.type, d.name, d.parent_from_sensor, d.params});
  if (index < static_cast<int>(prefab.actuators.size()))
    for (const ComponentDecl& d : prefab.actuators[index]) out.actuators.push_back({d.type, d.name, d.params});
  return out;
}

void add_link(BotPrefab& prefab, const BotLinkPrefab& link, const physics::JointDesc& joint) {
  const int index = static_cast<int>(prefab.articulation.links.size());
  const std::string where = "add_link(link '" + link.name + "', index " + std::to_string(index) + ")";
  if (index == 0 && link.parent_link != -1)
    throw Error(where + ": link.parent_link: the first link is the root and must have parent_link -1, got " +
                std::to_string(link.parent_link));
  if (index > 0 && (link.parent_link < 0 || link.parent_link >= index))
    throw Error(where + ": link.parent_link: must be the index of an earlier link (0.." + std::to_string(index - 1) + "), got " +
                std::to_string(link.parent_link));
  for (size_t k = 0; k < link.sensors.size(); ++k)
    if (link.sensors[k].type.empty()) throw Error(where + ": link.sensors[" + std::to_string(k) + "].type: must not be empty");
  for (size_t k = 0; k < link.actuators.size(); ++k)
    if (link.actuators[k].type.empty()) throw Error(where + ": link.actuators[" + std::to_string(k) + "].type: must not be empty");
  // one list of sensors and of actuators per link, also for links added before without any
  prefab.sensors.resize(index);
  prefab.actuators.resize(index);
  prefab.articulation.links.push_back(link);
  prefab.articulation.joints.push_back(joint);
  auto& sensors = prefab.sensors.emplace_back();
  for (const BotSensorPrefab& s : link.sensors) sensors.push_back({s.type, s.name, s.params, s.parent_from_sensor});
  auto& actuators = prefab.actuators.emplace_back();
  for (const BotActuatorPrefab& a : link.actuators) actuators.push_back({a.type, a.name, a.params, {}});
}

}  // namespace SUPERDEX_REAL_NAMESPACE
}  // namespace superdex::robotics
