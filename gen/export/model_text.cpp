#include "export/model_text.hpp"

#include <fmt/core.h>

#include <cmath>

#include "export/xml_writer.hpp"

namespace dyncc::exporting {

std::string coupling_text(const ExportModel& model, const Coupling& coupling) {
  std::string s = joint_name(model.bodies[static_cast<std::size_t>(coupling.body)]) + " =";
  for (std::size_t k = 0; k < coupling.terms.size(); ++k) {
    const CouplingTerm& t = coupling.terms[k];
    const std::string name = joint_name(model.bodies[static_cast<std::size_t>(t.body)]);
    const double size = std::abs(t.factor);
    const std::string magnitude = size == 1.0 ? name : number(size) + "*" + name;
    if (k == 0) {
      s += (t.factor < 0 ? " -" : " ") + magnitude;
    } else {
      s += (t.factor < 0 ? " - " : " + ") + magnitude;
    }
  }
  return s;
}

std::string coordinates_text(const ExportModel& model) {
  std::string s;
  for (std::size_t i = 0; i < model.coordinates.size(); ++i) {
    const CoordinateJoint& cj = model.coupling.coordinate_joints[i];
    const std::string& q = model.coordinates[i].name;
    if (!s.empty()) s += ", ";
    if (cj.body < 0) {
      s += q + ": a combination of joints";
      continue;
    }
    const std::string name = joint_name(model.bodies[static_cast<std::size_t>(cj.body)]);
    s += cj.scale == 1.0 ? fmt::format("{} = {}", q, name) : fmt::format("{} = {} / {}", q, name, number(cj.scale));
  }
  return s;
}

}  // namespace dyncc::exporting
