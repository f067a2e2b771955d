// `dyncc export --format urdf`: the file parses as XML (tinyxml2) into a tree of the
// description's links; what URDF cannot hold is listed (the Kraft arm's loop); and the tree, as
// written, has dyncc's dynamics: it is read back into the plain Eigen rigid-body algorithms of
// bench/eigen_rbd.hpp (themselves checked against dyncc in baseline_test.cpp), whose mass matrix
// and gravity torque, projected with G from the description's joint expressions, must equal
// dyncc's H (without the rotor inertias URDF cannot carry) and g, with URDF's gravity: 9.81
// along -z of the root link.
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "dynamics_support.hpp"
#include "eigen_rbd.hpp"
#include "export_random_robot.hpp"
#include "export_support.hpp"

namespace dyncc::test {
namespace {

constexpr double kUrdfTolerance = 1e-8;  // relative

struct UrdfLink {
  std::string name;
  double mass = 0.0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_rpy = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

struct UrdfJoint {
  std::string name, type, parent, child;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // URDF's default
  std::optional<std::pair<std::string, double>> mimic;
};

struct Urdf {
  std::string root;
  std::vector<UrdfLink> links;
  std::vector<UrdfJoint> joints;
};

Eigen::Vector3d triple(const char* text) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  if (text == nullptr) return v;
  std::istringstream in(text);
  in >> v.x() >> v.y() >> v.z();
  return v;
}

std::string attribute(const tinyxml2::XMLElement* e, const char* name) {
  const char* value = e == nullptr ? nullptr : e->Attribute(name);
  return value == nullptr ? "" : value;
}

Urdf parse_urdf(const std::filesystem::path& file) {
  Urdf urdf;
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.LoadFile(file.c_str()), tinyxml2::XML_SUCCESS) << file << ": " << doc.ErrorStr();
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (robot == nullptr) {
    ADD_FAILURE() << file << ": no <robot> element";
    return urdf;
  }
  for (const auto* e = robot->FirstChildElement("link"); e != nullptr; e = e->NextSiblingElement("link")) {
    UrdfLink link;
    link.name = attribute(e, "name");
    if (const auto* in = e->FirstChildElement("inertial")) {
      const auto* origin = in->FirstChildElement("origin");
      link.com = triple(origin == nullptr ? nullptr : origin->Attribute("xyz"));
      link.com_rpy = triple(origin == nullptr ? nullptr : origin->Attribute("rpy"));
      link.mass = in->FirstChildElement("mass")->DoubleAttribute("value");
      const auto* i = in->FirstChildElement("inertia");
      const double xx = i->DoubleAttribute("ixx"), yy = i->DoubleAttribute("iyy"), zz = i->DoubleAttribute("izz");
      const double xy = i->DoubleAttribute("ixy"), xz = i->DoubleAttribute("ixz"), yz = i->DoubleAttribute("iyz");
      link.inertia << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    }
    urdf.links.push_back(link);
  }
  std::set<std::string> children;
  for (const auto* e = robot->FirstChildElement("joint"); e != nullptr; e = e->NextSiblingElement("joint")) {
    UrdfJoint joint;
    joint.name = attribute(e, "name");
    joint.type = attribute(e, "type");
    joint.parent = attribute(e->FirstChildElement("parent"), "link");
    joint.child = attribute(e->FirstChildElement("child"), "link");
    if (const auto* origin = e->FirstChildElement("origin")) {
      joint.xyz = triple(origin->Attribute("xyz"));
      joint.rpy = triple(origin->Attribute("rpy"));
    }
    if (const auto* axis = e->FirstChildElement("axis")) joint.axis = triple(axis->Attribute("xyz"));
    if (const auto* mimic = e->FirstChildElement("mimic")) {
      joint.mimic = std::make_pair(attribute(mimic, "joint"), mimic->DoubleAttribute("multiplier", 1.0));
    }
    children.insert(joint.child);
    urdf.joints.push_back(joint);
  }
  for (const UrdfLink& l : urdf.links) {
    if (!children.contains(l.name)) urdf.root = l.name;
  }
  return urdf;
}

/// URDF's rpy: fixed-axis roll about x, then pitch about y, then yaw about z.
Eigen::Matrix3d from_rpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

std::filesystem::path export_urdf(const std::filesystem::path& description, DynccRun* run_out = nullptr) {
  const std::filesystem::path out = output_path(description.stem().string() + ".urdf");
  const DynccRun run = run_dyncc("export " + quoted(description) + " --format urdf -o " + quoted(out));
  EXPECT_EQ(run.exit_code, 0) << run.errors;
  if (run_out != nullptr) *run_out = run;
  return out;
}

// ---- structure

TEST(ExportUrdf, KraftListsTheDroppedLoopAndCouplings) {
  DynccRun run;
  const std::filesystem::path file = export_urdf(robots_dir() / "kraft.yaml", &run);
  EXPECT_NE(run.errors.find("warning: loops.elbow_parallelogram: URDF export drops the loop 'elbow_parallelogram'"),
            std::string::npos)
      << run.errors;
  const std::string text = read_text(file);
  EXPECT_NE(text.find("<!-- dropped: loop 'elbow_parallelogram' (URDF describes trees only) -->"), std::string::npos);
  // The forearm and the coupler follow two joints each, which no URDF mimic can say.
  EXPECT_NE(text.find("dropped: coupling forearm_joint ="), std::string::npos);
  EXPECT_NE(text.find("dropped: coupling coupler_joint ="), std::string::npos);
  const Urdf urdf = parse_urdf(file);
  EXPECT_EQ(urdf.root, "base");
  EXPECT_EQ(urdf.links.size(), 6U);  // base + five bodies
  EXPECT_EQ(urdf.joints.size(), 5U);
}

/// The URDF of a description is a tree of its links under `base` (under `world` when the
/// description's gravity is not along -z).
void check_structure(const std::filesystem::path& description) {
  const auto loaded = robot::load_robot(description);
  ASSERT_TRUE(loaded.ok());
  const robot::RobotDescription& robot = *loaded.robot;
  const Urdf urdf = parse_urdf(export_urdf(description));
  const std::array<double, 3> g = robot.gravity_values();
  const bool turned = !(g[0] == 0.0 && g[1] == 0.0 && g[2] < 0.0);
  EXPECT_EQ(urdf.root, turned ? "world" : "base");
  EXPECT_EQ(urdf.links.size(), robot.links.size() + (turned ? 2 : 1));
  EXPECT_EQ(urdf.joints.size(), robot.links.size() + (turned ? 1 : 0));
  std::set<std::string> link_names, child_names;
  for (const UrdfLink& l : urdf.links) EXPECT_TRUE(link_names.insert(l.name).second) << "duplicate link " << l.name;
  for (const UrdfJoint& j : urdf.joints) {
    EXPECT_TRUE(link_names.contains(j.parent)) << j.name << ": unknown parent " << j.parent;
    EXPECT_TRUE(link_names.contains(j.child)) << j.name << ": unknown child " << j.child;
    EXPECT_TRUE(child_names.insert(j.child).second) << j.child << " has two parent joints";
  }
  for (const robot::Link& l : robot.links) EXPECT_TRUE(child_names.contains(l.name)) << l.name << " is missing";
}

TEST(ExportUrdf, EveryShippedRobotIsATreeOfItsLinks) {
  for (const auto& path : shipped_robots()) {
    SCOPED_TRACE(path.filename().string());
    check_structure(path);
  }
}

// ---- dynamics of the tree as written

/// The URDF's tree in the Eigen baseline's terms, bodies parents first from `base`; gravity is
/// URDF's, turned into the base frame through a `world` root if there is one.
bench::RigidBodyTree tree_from_urdf(const Urdf& urdf, const robot::RobotDescription& robot, const Eigen::VectorXd& q0,
                                    JointVariables& joints) {
  bench::RigidBodyTree tree;
  std::map<std::string, const UrdfLink*> links;
  for (const UrdfLink& l : urdf.links) links[l.name] = &l;
  Eigen::Matrix3d base_in_root = Eigen::Matrix3d::Identity();
  for (const UrdfJoint& j : urdf.joints) {
    if (j.child == "base") base_in_root = from_rpy(j.rpy);
  }
  tree.gravity = base_in_root.transpose() * Eigen::Vector3d(0, 0, -9.81);
  std::map<std::string, int> index{{"base", -1}};
  std::vector<Eigen::RowVectorXd> rows;
  for (bool added = true; added;) {  // breadth first: a joint is taken once its parent is placed
    added = false;
    for (const UrdfJoint& j : urdf.joints) {
      if (!index.contains(j.parent) || index.contains(j.child)) continue;
      added = true;
      const UrdfLink& link = *links.at(j.child);
      EXPECT_TRUE(j.type == "fixed" || j.axis == Eigen::Vector3d::UnitZ()) << j.name << ": axis is not z";
      EXPECT_TRUE(link.com_rpy.isZero(0.0)) << link.name << ": inertial frame is turned";
      bench::RigidBody b;
      b.parent = index.at(j.parent);
      b.joint = j.type == "fixed" ? bench::JointKind::Fixed
                                  : (j.type == "prismatic" ? bench::JointKind::Prismatic : bench::JointKind::Revolute);
      b.rotation = from_rpy(j.rpy);
      b.position = j.xyz;
      b.mass = link.mass;
      b.com = link.com;
      b.inertia = link.inertia;
      index[j.child] = static_cast<int>(tree.bodies.size());
      tree.bodies.push_back(b);
      if (b.joint != bench::JointKind::Fixed) {
        const auto l = robot.find_link(j.child);
        EXPECT_TRUE(l.has_value()) << j.child;
        rows.push_back(joints.gradient(static_cast<std::size_t>(*l), q0));
      }
    }
  }
  tree.coupling.resize(static_cast<Eigen::Index>(rows.size()), q0.size());
  for (std::size_t r = 0; r < rows.size(); ++r) tree.coupling.row(static_cast<Eigen::Index>(r)) = rows[r];
  tree.armature = Eigen::VectorXd::Zero(q0.size());
  return tree;
}

struct UrdfWorst {
  double H = 0, g = 0;
};

UrdfWorst check_urdf_dynamics(const std::filesystem::path& description) {
  UrdfWorst w;
  const std::string file = description.filename().string();
  const auto d = derive_file(description);
  if (!d) return w;
  const Urdf urdf = parse_urdf(export_urdf(description));
  JointVariables joints(d->robot);
  const auto n = static_cast<Eigen::Index>(d->robot.coordinates.size());
  bench::EigenRbd rbd(tree_from_urdf(urdf, d->robot, Eigen::VectorXd::Zero(n), joints));

  // A mimic joint must follow its joint as the description's expressions do.
  std::map<std::string, std::size_t> link_of_joint;
  for (const UrdfJoint& j : urdf.joints) {
    if (const auto l = d->robot.find_link(j.child)) link_of_joint[j.name] = static_cast<std::size_t>(*l);
  }
  for (const UrdfJoint& j : urdf.joints) {
    if (!j.mimic) continue;
    const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, 0.2, 0.7);
    const Eigen::RowVectorXd follows = j.mimic->second * joints.gradient(link_of_joint.at(j.mimic->first), q);
    EXPECT_LT((joints.gradient(link_of_joint.at(j.name), q) - follows).cwiseAbs().maxCoeff(), 1e-12) << j.name;
  }

  const Eigen::VectorXd standard = d->numeric->nominal_standard_values();
  const Eigen::VectorXd rotor = rotor_inertias(d->robot);
  std::mt19937_64 rng(7);
  for (int k = 0; k < 20; ++k) {
    const dyn::State s = random_state(n, rng);
    const dyn::Evaluation e = d->numeric->evaluate(s, standard, false);
    Eigen::MatrixXd H(n, n);
    Eigen::VectorXd g(n);
    rbd.mass_matrix(s.q.data(), H.data());
    rbd.gravity_torque(s.q.data(), g.data());
    const Eigen::MatrixXd expected_h = e.H - Eigen::MatrixXd(rotor.asDiagonal());
    w.H = std::max(w.H, relative_difference(H, expected_h, max_abs(expected_h)));
    // Relative to g, unless gravity hardly loads the joints (then rounding dominates g).
    w.g = std::max(w.g, relative_difference(g, e.g, std::max(max_abs(e.g), 1e-6 * max_abs(e.H))));
  }
  EXPECT_LT(w.H, kUrdfTolerance) << file << ": the URDF tree's H differs from dyncc's (rotors aside)";
  EXPECT_LT(w.g, kUrdfTolerance) << file << ": the URDF tree's gravity torque differs from dyncc's";
  return w;
}

void check_shipped_urdf(const std::string& file) {
  const UrdfWorst w = check_urdf_dynamics(robots_dir() / file);
  std::cout << file << " URDF: max relative error H " << scientific(w.H) << "  g " << scientific(w.g) << "\n";
}

TEST(ExportUrdf, KraftTreeHasDynccDynamics) { check_shipped_urdf("kraft.yaml"); }
TEST(ExportUrdf, Puma560TreeHasDynccDynamics) { check_shipped_urdf("puma560.yaml"); }
TEST(ExportUrdf, PandaTreeHasDynccDynamics) { check_shipped_urdf("panda.yaml"); }
// Gravity along -y: the base is turned under a `world` root.
TEST(ExportUrdf, PlanarArmTreeHasDynccDynamicsUnderTurnedBase) { check_shipped_urdf("planar_2link.yaml"); }

// Random descriptions (export_random_robot.hpp): mimic joints, welded links, prismatic joints,
// gravity in other directions; URDF keeps the description's own mass properties.
TEST(ExportUrdf, RandomDescriptionsAreTreesWithDynccDynamics) {
  std::mt19937_64 rng(4243);
  UrdfWorst largest;
  for (int r = 0; r < 12; ++r) {
    const std::string label = cat({"random", std::to_string(r)});
    const std::string text = random_export_robot(rng, r);
    const std::filesystem::path yaml = output_path(label + ".yaml");
    std::ofstream(yaml) << text;
    check_structure(yaml);
    const UrdfWorst w = check_urdf_dynamics(yaml);
    largest.H = std::max(largest.H, w.H);
    largest.g = std::max(largest.g, w.g);
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << label << ":\n" << text;
      return;
    }
  }
  std::cout << "random descriptions URDF: max relative error H " << scientific(largest.H) << "  g "
            << scientific(largest.g) << "\n";
}

}  // namespace
}  // namespace dyncc::test
