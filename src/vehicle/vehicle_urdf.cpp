#include "propulsion_estimator/vehicle/vehicle_urdf.h"

#include <map>
#include <regex>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <console_bridge/console.h>
#include <tinyxml.h>
#include <urdf_parser/urdf_parser.h>

#include "propulsion_estimator/common/config_error.h"
#include "propulsion_estimator/common/text_file.h"
#include "propulsion_estimator/common/yaml_map.h"

namespace propulsion_estimator {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  transform.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                           .normalized()
                           .toRotationMatrix();
  return transform;
}

// Pose of a link in the root link's frame (refuseLinkLoops has made sure the walk ends).
Eigen::Isometry3d linkPose(const urdf::ModelInterface& model, const std::string& link_name) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  urdf::LinkConstSharedPtr link = model.getLink(link_name);
  while (link && link->parent_joint) {
    pose = toIsometry(link->parent_joint->parent_to_joint_origin_transform) * pose;
    link = model.getLink(link->parent_joint->parent_link_name);
  }
  return pose;
}

// urdfdom accepts a joint whose child is one of its ancestors (a loop beside the root's tree),
// whose links the walk to the root would never leave, and links a loop's links to one another by
// shared_ptr, never freed even when it refuses the description. So the joints' parent -> child
// edges are read first from the same document (TinyXML, urdfdom's XML layer) and a loop refused:
// ConfigError naming the joint that closes it.
void refuseLinkLoops(const std::string& xml, const std::string& source) {
  TiXmlDocument document;
  document.Parse(xml.c_str());
  const TiXmlElement* robot = document.Error() ? nullptr : document.FirstChildElement("robot");
  if (!robot) return;  // urdfdom refuses it
  struct Edge {
    std::string child;
    std::string joint;
  };
  std::map<std::string, std::vector<Edge>> children;  // parent link -> its joints' child links
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint; joint = joint->NextSiblingElement("joint")) {
    const TiXmlElement* parent = joint->FirstChildElement("parent");
    const TiXmlElement* child = joint->FirstChildElement("child");
    const char* name = joint->Attribute("name");
    const char* parent_link = parent ? parent->Attribute("link") : nullptr;
    const char* child_link = child ? child->Attribute("link") : nullptr;
    if (name && parent_link && child_link) children[parent_link].push_back({child_link, name});
  }
  // Depth-first from every link, without recursion (a description may chain thousands of links):
  // an edge back to a link on the current path closes a loop.
  enum class State { kOnPath, kDone };
  std::map<std::string, State> state;
  for (const auto& [root, edges] : children) {
    if (state.count(root)) continue;
    std::vector<std::pair<std::string, std::size_t>> path = {{root, 0}};  // link, next edge
    state[root] = State::kOnPath;
    while (!path.empty()) {
      auto& [link, next] = path.back();
      const auto found = children.find(link);
      if (found == children.end() || next == found->second.size()) {
        state[link] = State::kDone;
        path.pop_back();
        continue;
      }
      const Edge& edge = found->second[next++];
      const auto seen = state.find(edge.child);
      if (seen == state.end()) {
        state[edge.child] = State::kOnPath;
        path.push_back({edge.child, 0});
      } else if (seen->second == State::kOnPath) {
        throw ConfigError(source + ": joint " + edge.joint + ": closes a loop of links (a link would be its own ancestor)");
      }
    }
  }
}

std::optional<MassProperties> massProperties(const urdf::ModelInterface& model) {
  struct Part {
    double mass;
    Eigen::Vector3d position;
    Eigen::Matrix3d inertia;  // about the part's own centre, in the root frame
  };
  std::vector<Part> parts;
  for (const auto& [name, link] : model.links_) {
    if (!link->inertial) continue;
    const urdf::Inertial& in = *link->inertial;
    const Eigen::Isometry3d pose = linkPose(model, name) * toIsometry(in.origin);
    Eigen::Matrix3d local;
    local << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    parts.push_back({in.mass, pose.translation(), pose.linear() * local * pose.linear().transpose()});
  }
  if (parts.empty()) return std::nullopt;
  MassProperties total;
  for (const Part& part : parts) {
    total.mass_kg += part.mass;
    total.centre_of_mass_m += part.mass * part.position;
  }
  if (total.mass_kg <= 0.0) return std::nullopt;
  total.centre_of_mass_m /= total.mass_kg;
  for (const Part& part : parts) {
    const Eigen::Vector3d r = part.position - total.centre_of_mass_m;
    total.inertia_kg_m2 += part.inertia + part.mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  return total;
}

}  // namespace

Vehicle vehicleFromUrdf(const std::string& xml, const std::string& source) {
  // urdfdom reports parse errors through console_bridge on stderr; ours is the one line that counts.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  // TinyXML (urdfdom's XML layer) steps over a multi-byte UTF-8 character whole, past the end of a
  // text cut inside one (a fuzz finding): NUL padding longer than any character keeps it in the buffer.
  const std::string padded = xml + std::string(8, '\0');
  refuseLinkLoops(padded, source);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(padded);
  if (!model) throw ConfigError(source + ": not a valid URDF robot description");

  // Motor numbers are small: at most 32 RC output channels.
  static const std::regex kRotorJoint("rotor_([0-9]{1,2})_joint");
  std::map<int, Rotor> rotors;
  for (const auto& [name, joint] : model->joints_) {
    std::smatch match;
    if (!std::regex_match(name, match, kRotorJoint)) continue;
    if (joint->type != urdf::Joint::CONTINUOUS && joint->type != urdf::Joint::REVOLUTE) {
      throw ConfigError(source + ": joint " + name + ": a rotor joint must be continuous (or revolute)");
    }
    const int number = std::stoi(match[1]);
    const Eigen::Isometry3d pose = linkPose(*model, joint->child_link_name);
    Rotor rotor;
    rotor.name = joint->child_link_name;
    rotor.position_m = pose.translation();
    rotor.thrust_axis = pose.linear() * Eigen::Vector3d::UnitZ();
    rotor.spin_direction = joint->axis.z >= 0.0 ? 1 : -1;
    rotors.emplace(number, rotor);
  }
  if (rotors.empty()) throw ConfigError(source + ": no rotor joints (expected joints named rotor_1_joint, rotor_2_joint, ...)");
  Vehicle vehicle;
  int expected = 1;
  for (const auto& [number, rotor] : rotors) {
    if (number != expected) {
      throw ConfigError(source + ": rotor_" + std::to_string(expected) + "_joint is missing (rotors are numbered 1.." +
                        std::to_string(rotors.size()) + " without gaps)");
    }
    vehicle.rotors.push_back(rotor);
    ++expected;
  }
  vehicle.empty_mass = massProperties(*model);
  return vehicle;
}

Vehicle loadVehicleUrdf(const std::string& path) { return vehicleFromUrdf(readTextFile(path), path); }

}  // namespace propulsion_estimator
