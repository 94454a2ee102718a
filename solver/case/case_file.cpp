#include "case/case_file.hpp"

#include <algorithm>
#include <cmath>

#include "porous/porous_setup.hpp"
#include "sand/sand_section.hpp"
#include "water/water_section.hpp"

namespace sc {

namespace {

void check_box(JsonObject& o, const std::vector<double>& lo, const std::vector<double>& hi) {
  for (std::size_t d = 0; d < lo.size(); ++d)
    if (!(hi[d] > lo[d])) o.fail("max", "must exceed min in every coordinate (axis " + std::to_string(d) + ")");
}

void read_tank(JsonObject o, CaseSpec& c) {
  TankSpec t;
  t.min = o.numbers("min", c.dimension);
  t.max = o.numbers("max", c.dimension);
  check_box(o, t.min, t.max);
  JsonObject sides = o.object("sides");
  for (int d = 0; d < c.dimension; ++d)
    for (const int outward : {-1, 1}) {
      const std::string rule = sides.one_of(TankSpec::side_name(d, outward), {"no_slip", "slip", "open"});
      t.rules[TankSpec::side_index(d, outward)] =
          rule == "no_slip" ? WallRule::NoSlip : (rule == "slip" ? WallRule::Slip : WallRule::Open);
    }
  sides.finish();
  t.collision = o.boolean("collision", false);
  o.finish();
  c.tank = t;
}

void read_time(JsonObject o, CaseSpec& c) {
  c.end_time = o.positive("end");
  c.dt_max = o.positive("dt", 0.001);
  c.cfl = o.in_range("cfl", 0.0, 1.0, false, 0.0);
  c.frame_interval = o.non_negative("frame_interval", 0.0);
  c.relax_until = o.non_negative("relax_until", 0.0);
  c.relax_rate = o.non_negative("relax_rate", 0.0);
  if (c.relax_until >= c.end_time) o.fail("relax_until", "must be earlier than time.end");
  if (c.frame_interval > 0.0 && c.frame_interval < c.dt_max)
    o.fail("frame_interval", "must be 0 (first and last frame only) or at least time.dt = " + json(c.dt_max).dump() +
                                 " (one frame per step at most)");
  o.finish();
}

std::vector<std::string> read_tier_methods(JsonObject& t, const CaseSpec& c) {
  const json& list = t.raw("methods");
  if (!list.is_array() || list.empty()) t.fail("methods", "must be a non-empty array of method names");
  std::vector<std::string> names;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string where = "methods/" + std::to_string(k);
    if (!list[k].is_string() || !c.supports(list[k].get<std::string>()))
      t.fail(where, "must name a method the case supports (its \"method\" or a key of \"methods\")");
    if (std::find(names.begin(), names.end(), list[k].get<std::string>()) != names.end()) t.fail(where, "is listed twice");
    names.push_back(list[k].get<std::string>());
  }
  return names;
}

ConvergenceSpec read_convergence(JsonObject o) {
  ConvergenceSpec spec;
  spec.spacings = o.numbers("spacings");
  if (spec.spacings.size() < 2) o.fail("spacings", "a study needs at least two spacings");
  for (std::size_t k = 0; k < spec.spacings.size(); ++k) {
    if (!(spec.spacings[k] > 0.0)) o.fail("spacings", "every spacing must be > 0");
    if (k > 0 && !(spec.spacings[k] < spec.spacings[k - 1])) o.fail("spacings", "must be listed coarse to fine, each smaller");
  }
  JsonObject metrics = o.object("metrics");
  for (const auto& [name, value] : o.raw("metrics").items()) spec.orders[name] = metrics.positive(name);
  if (spec.orders.empty()) o.fail("metrics", "must name at least one metric with the order it should reach");
  metrics.finish();
  o.finish();
  return spec;
}

void read_tiers(JsonObject o, CaseSpec& c) {
  for (const char* tier : {"quick", "full"}) {
    if (std::string(tier) == "quick" && !o.has(tier)) continue;  // a scene outside the quick (CI) suite
    JsonObject t = o.object(tier);
    TierSpec spec;
    spec.spacings = t.numbers("spacings");
    for (double s : spec.spacings)
      if (!(s > 0.0)) t.fail("spacings", "every spacing must be > 0");
    spec.end_time = t.positive("end_time", 0.0);
    if (t.has("methods")) spec.methods = read_tier_methods(t, c);
    t.finish();
    c.tiers[tier] = spec;
  }
  o.finish();
}

/// A block must not reach into the wall layers of a closed tank side: it must lie within the
/// tank's box on every side that is not open.
void check_blocks_inside_tank(const CaseSpec& c) {
  for (std::size_t k = 0; k < c.blocks.size(); ++k)
    for (int d = 0; d < c.dimension; ++d) {
      const BlockSpec& b = c.blocks[k];
      const std::string where = "/blocks/" + std::to_string(k);
      if (c.tank->closed(d, -1) && b.min[d] < c.tank->min[d])
        throw InputError(c.file, where + "/min", "block overlaps the tank wall " + TankSpec::side_name(d, -1) + " (closed side): it must lie inside the tank");
      if (c.tank->closed(d, 1) && b.max[d] > c.tank->max[d])
        throw InputError(c.file, where + "/max", "block overlaps the tank wall " + TankSpec::side_name(d, 1) + " (closed side): it must lie inside the tank");
    }
}

}  // namespace

CaseSpec load_case(const std::string& path) { return load_case(read_json_file(path), path); }

CaseSpec load_case(const json& doc, const std::string& path) {
  JsonObject o(doc, "", path);
  CaseSpec c;
  c.file = path;
  c.name = o.string("name");
  c.description = o.string("description", "");
  c.dimension = static_cast<int>(o.integer("dimension", 2, 3));
  JsonObject domain = o.object("domain");
  c.domain_min = domain.numbers("min", c.dimension);
  c.domain_max = domain.numbers("max", c.dimension);
  check_box(domain, c.domain_min, c.domain_max);
  domain.finish();
  c.gravity = o.numbers("gravity", c.dimension);
  read_time(o.object("time"), c);
  c.support_ratio = o.in_range("support_ratio", 1.0, 4.0, false, 2.0);
  c.density_window = o.non_negative("density_window", 0.0);
  const WaterSection water = read_water(o.object("water"));
  c.water = water.params;
  c.eos = water.eos;
  c.artificial_viscosity = water.artificial_viscosity;
  if (o.has("sand")) {
    c.sand = read_sand(o.object("sand"));
    c.has_sand = true;
  }
  if (o.has("porous")) c.porous = read_porous(o.object("porous"), c.water.rest_density);
  if (o.has("adaptive")) {
    c.adaptive = read_adaptivity(o.object("adaptive"), c.dimension);
    if (c.adaptive->adapt_sand && !c.has_sand) o.fail("adaptive", "phases names sand but the case has no \"sand\" section");
  }
  for (JsonObject b : o.objects("blocks")) {
    BlockSpec block;
    const std::string fill = b.one_of("phase", {"water", "sand", "porous_bed"});
    if (fill == "porous_bed" && !c.porous) b.fail("phase", "a porous_bed block needs the \"porous\" section");
    if (fill == "sand" && !c.has_sand) b.fail("phase", "a sand block needs the \"sand\" section");
    block.fill = fill == "sand" ? BlockFill::Sand : (fill == "water" ? BlockFill::Water : BlockFill::PorousBed);
    block.min = b.numbers("min", c.dimension);
    block.max = b.numbers("max", c.dimension);
    check_box(b, block.min, block.max);
    for (int d = 0; d < c.dimension; ++d)
      if (block.min[d] < c.domain_min[d] || block.max[d] > c.domain_max[d])
        b.fail("max", "block must lie inside the domain");
    if (b.has("angular_velocity")) {
      if (fill == "porous_bed") b.fail("angular_velocity", "a porous_bed block is a fixed skeleton: it cannot spin");
      block.angular_velocity = b.numbers("angular_velocity", c.dimension == 3 ? 3 : 1);
    }
    b.finish();
    c.blocks.push_back(block);
  }
  if (o.has("meshes")) {
    if (c.dimension != 3) o.fail("meshes", "meshes need \"dimension\": 3");
    for (JsonObject m : o.objects("meshes"))
      c.meshes.push_back(read_mesh(m, path, c.has_sand));
  }
  if (o.has("tank")) {
    read_tank(o.object("tank"), c);
    check_blocks_inside_tank(c);
  }
  c.method = o.string("method", "sph");
  if (o.has("methods")) {
    c.methods = o.raw("methods");
    if (!c.methods.is_object()) o.fail("methods", "must be an object: {method name: {its parameters}}");
    for (const auto& [name, params] : c.methods.items())
      if (!params.is_object()) o.fail("methods", "the parameters of method \"" + name + "\" must be an object");
  }
  c.validation = o.has("validation") ? o.raw("validation") : json::object();
  c.render = o.has("render") ? o.raw("render") : json::object();
  if (o.has("regression")) c.regression = read_regression(o.object("regression"));
  c.parameters_hash = parameters_hash(doc);
  read_tiers(o.object("tiers"), c);
  if (o.has("convergence")) c.convergence = read_convergence(o.object("convergence"));
  o.finish();
  double largest_spacing = 0.0;
  for (const auto& [name, tier] : c.tiers)
    largest_spacing = std::max(largest_spacing, *std::max_element(tier.spacings.begin(), tier.spacings.end()));
  for (const auto& b : c.blocks)
    for (int d = 0; d < c.dimension; ++d)
      if (b.max[d] - b.min[d] < largest_spacing)
        throw InputError(path, "/blocks", "every block must be at least one particle spacing wide");
  return c;
}

}  // namespace sc
