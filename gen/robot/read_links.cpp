// Reader for `links`: D-H geometry, joint type and inertial entries of each link.
#include <fmt/core.h>

#include "robot/load_state.hpp"
#include "robot/spelling.hpp"

namespace dyncc::robot::detail {

namespace {

const std::vector<std::string> kLinkFields = {"name",  "parent", "joint", "a",       "alpha",      "d",
                                              "theta", "mass",   "com",   "inertia", "description"};
const std::vector<std::string> kInertiaFields = {"xx", "yy", "zz", "xy", "xz", "yz"};

class LinkReader {
 public:
  LinkReader(YamlReader& reader, LoadState& state, const SymbolScope& scope, int index)
      : reader_(reader), state_(state), scope_(scope), index_(index) {}

  void read(const Located& entry) {
    link_.location = entry.location;
    if (!reader_.expect_map(entry, "a link with name, parent, joint, D-H parameters and inertial parameters")) return;
    fields_ = reader_.fields(entry, kLinkFields);
    for (const auto& [key, value] : fields_) link_.field_locations.emplace(key, value.location);
    read_name(entry);
    if (reader_.require(fields_, entry, "parent", "'base' or the name of an earlier link")) {
      if (auto parent = reader_.identifier(fields_.at("parent"), "a link name or 'base'")) link_.parent_name = *parent;
    }
    read_joint(entry);
    read_geometry();
    read_inertial(entry);
    if (const auto description = fields_.find("description"); description != fields_.end()) {
      if (auto text = reader_.text(description->second, "free text")) link_.description = *text;
    }
  }

  Link take() { return std::move(link_); }

 private:
  void read_name(const Located& entry) {
    if (!reader_.require(fields_, entry, "name")) return;
    const Located& value = fields_.at("name");
    auto name = reader_.identifier(value, "a link name");
    if (!name) return;
    if (*name == "base") {
      reader_.sink().error(value.location, value.path, "'base' is reserved for the fixed base; choose another name");
      return;
    }
    if (const auto earlier = state_.robot.find_link(*name)) {
      reader_.sink().error(value.location, value.path,
                           fmt::format("duplicate link name '{}' (first given on line {})", *name,
                                       state_.robot.links[static_cast<std::size_t>(*earlier)].location.line));
      return;
    }
    link_.name = *name;
  }

  void read_joint(const Located& entry) {
    if (!reader_.require(fields_, entry, "joint", "revolute or prismatic")) return;
    const Located& value = fields_.at("joint");
    const auto word = reader_.text(value, "revolute or prismatic");
    if (!word) return;
    if (*word == "revolute") {
      link_.joint = JointType::Revolute;
    } else if (*word == "prismatic") {
      link_.joint = JointType::Prismatic;
    } else {
      reader_.sink().error(value.location, value.path,
                           fmt::format("expected 'revolute' or 'prismatic', got '{}'", word->substr(0, 40)),
                           closest_match(*word, {"revolute", "prismatic"}));
      return;
    }
    joint_known_ = true;
  }

  void read_geometry() {
    auto read = [&](const char* key, sym::Expr& target) {
      const auto found = fields_.find(key);
      if (found == fields_.end()) return;  // D-H entries not written are 0
      if (auto expr = read_expression(reader_, found->second, scope_)) target = *expr;
    };
    read("a", link_.a);
    read("alpha", link_.alpha);
    read("d", link_.d);
    read("theta", link_.theta);
    // The joint variable is never assumed (a default would silently pick a coordinate).
    if (joint_known_) {
      const char* variable = link_.joint == JointType::Revolute ? "theta" : "d";
      if (!fields_.contains(variable)) {
        reader_.sink().error(link_.location, path(),
                             fmt::format("missing required field '{}' (the joint variable of a {} link, e.g. '{}: "
                                         "q1'; write it even when it is just a coordinate)",
                                         variable, to_string(link_.joint), variable));
      }
    }
  }

  void read_inertial(const Located& entry) {
    if (reader_.require(fields_, entry, "mass",
                        "a number, or the name of an unknown; write 'mass: 0' for a massless frame")) {
      if (auto mass = record_entry(reader_, state_, fields_.at("mass"), ParameterRole::Mass, index_, -1))
        link_.mass = *mass;
    }
    if (const auto com = fields_.find("com"); com != fields_.end()) {
      if (auto items = reader_.fixed_sequence(com->second, 3, "x, y, z of the centre of mass in the link frame")) {
        for (std::size_t i = 0; i < 3; ++i) {
          const Located& item = (*items)[i];
          link_.field_locations.emplace(fmt::format("com[{}]", i), item.location);
          if (auto value = record_entry(reader_, state_, item, ParameterRole::CenterOfMass, index_, -1)) {
            link_.com[i] = *value;
          }
        }
      }
    }
    if (const auto inertia = fields_.find("inertia"); inertia != fields_.end()) {
      const Located& map = inertia->second;
      if (!reader_.expect_map(map, "entries xx, yy, zz, xy, xz, yz of the inertia tensor about the centre of mass"))
        return;
      const auto entries = reader_.fields(map, kInertiaFields);
      sym::Expr* targets[] = {&link_.inertia.xx, &link_.inertia.yy, &link_.inertia.zz,
                              &link_.inertia.xy, &link_.inertia.xz, &link_.inertia.yz};
      for (std::size_t i = 0; i < kInertiaFields.size(); ++i) {
        const auto found = entries.find(kInertiaFields[i]);
        if (found == entries.end()) continue;  // entries left out are 0
        link_.field_locations.emplace("inertia." + kInertiaFields[i], found->second.location);
        if (auto value = record_entry(reader_, state_, found->second, ParameterRole::Inertia, index_, -1)) {
          *targets[i] = *value;
        }
      }
    }
  }

  [[nodiscard]] std::string path() const { return fmt::format("links[{}]", index_); }

  YamlReader& reader_;
  LoadState& state_;
  const SymbolScope& scope_;
  int index_;
  Link link_;
  std::map<std::string, Located> fields_;
  bool joint_known_ = false;
};

}  // namespace

void read_links(YamlReader& reader, LoadState& state, const Located& value) {
  if (!reader.expect_sequence(value, "a list of links, parents before children")) return;
  const std::vector<Located> entries = reader.elements(value);
  if (entries.empty() && value.node.size() == 0) {
    reader.sink().error(value.location, value.path, "expected at least one link, got an empty list");
    return;
  }
  const SymbolScope scope = state.geometry_scope();
  for (const Located& entry : entries) {
    LinkReader link_reader(reader, state, scope, static_cast<int>(state.robot.links.size()));
    link_reader.read(entry);
    state.robot.links.push_back(link_reader.take());
  }
  state.links_readable = true;
}

}  // namespace dyncc::robot::detail
