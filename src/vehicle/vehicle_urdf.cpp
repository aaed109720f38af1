#include "propulsion_estimator/vehicle/vehicle_urdf.h"

#include <map>
#include <regex>

#include <Eigen/Geometry>
#include <console_bridge/console.h>
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

// Pose of a link in the root link's frame. urdfdom accepts a joint whose child is one of its own
// ancestors (a loop apart from the root's tree), which the walk up to the root would never leave:
// ConfigError naming the joint found more often on the way than there are joints.
Eigen::Isometry3d linkPose(const urdf::ModelInterface& model, const std::string& link_name, const std::string& source) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  urdf::LinkConstSharedPtr link = model.getLink(link_name);
  std::size_t steps = 0;
  while (link && link->parent_joint) {
    if (++steps > model.joints_.size()) {
      throw ConfigError(source + ": joint " + link->parent_joint->name +
                        ": closes a loop of links (a link would be its own ancestor)");
    }
    pose = toIsometry(link->parent_joint->parent_to_joint_origin_transform) * pose;
    link = model.getLink(link->parent_joint->parent_link_name);
  }
  return pose;
}

std::optional<MassProperties> massProperties(const urdf::ModelInterface& model, const std::string& source) {
  struct Part {
    double mass;
    Eigen::Vector3d position;
    Eigen::Matrix3d inertia;  // about the part's own centre, in the root frame
  };
  std::vector<Part> parts;
  for (const auto& [name, link] : model.links_) {
    if (!link->inertial) continue;
    const urdf::Inertial& in = *link->inertial;
    const Eigen::Isometry3d pose = linkPose(model, name, source) * toIsometry(in.origin);
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

// urdfdom holds a link's children by shared_ptr: the links of a loop own one another and would
// outlive the model. Dropping every link's children when the model is done with frees them all.
struct LinkTreeRelease {
  urdf::ModelInterface& model;
  ~LinkTreeRelease() {
    for (const auto& [name, link] : model.links_) {
      link->child_links.clear();
      link->child_joints.clear();
    }
  }
};

}  // namespace

Vehicle vehicleFromUrdf(const std::string& xml, const std::string& source) {
  // urdfdom reports parse errors through console_bridge on stderr; ours is the one line that counts.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  if (!model) throw ConfigError(source + ": not a valid URDF robot description");
  const LinkTreeRelease release{*model};

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
    const Eigen::Isometry3d pose = linkPose(*model, joint->child_link_name, source);
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
  vehicle.empty_mass = massProperties(*model, source);
  return vehicle;
}

Vehicle loadVehicleUrdf(const std::string& path) { return vehicleFromUrdf(readTextFile(path), path); }

}  // namespace propulsion_estimator
