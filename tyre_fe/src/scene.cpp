#include "tyre_fe/scene.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

#include "cosim/error.hpp"

namespace tyre_fe {
namespace sc = cosim::scene;
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string resolve(const std::string& scene_file, const std::string& ref) {
  return ref.empty() || ref.front() == '/' ? ref : cosim::folder_of(scene_file) + "/" + ref;
}

// The materials of the scene: the file's regions, replaced by inline regions of
// the same name; each with the locator of where it was written.
struct RegionEntry {
  sc::TyreRegionMaterial material;
  std::optional<cosim::FieldLocator> where;
};
struct Materials {
  std::array<std::optional<RegionEntry>, kRegionCount> regions;
  std::string source;
  std::unique_ptr<google::protobuf::TextFormat::ParseInfoTree> file_tree;
  std::string file;
};

Materials collect_materials(const cosim::LoadedScene& loaded, cosim::ValidationReport& r) {
  Materials out;
  const auto& tyre = loaded.message.tyre();
  const auto loc = loaded.locator().child("tyre");
  auto take = [&](const sc::TyreRegionMaterial& m, const cosim::FieldLocator& where) {
    Region region;
    try {
      region = region_from_name(m.region());
    } catch (const cosim::Error& e) {
      r.fail(where.where("region"), e.what());
      return;
    }
    out.regions[static_cast<int>(region)] = RegionEntry{m, where};
  };
  if (!tyre.materials_file().empty()) {
    out.file = resolve(loaded.file, tyre.materials_file());
    sc::TyreMaterialSet set;
    out.file_tree = std::make_unique<google::protobuf::TextFormat::ParseInfoTree>();
    cosim::parse_text_file(out.file, set, out.file_tree.get());  // throws with file:line
    const cosim::FieldLocator file_loc(sc::TyreMaterialSet::descriptor(), "",
                                       {{out.file, out.file_tree.get()}}, nullptr);
    out.source = set.source();
    for (int i = 0; i < set.regions_size(); ++i) take(set.regions(i), file_loc.child("regions", i));
  }
  for (int i = 0; i < tyre.materials_size(); ++i) take(tyre.materials(i), loc.child("materials", i));
  for (int k = 0; k < kRegionCount; ++k)
    if (!out.regions[k])
      r.fail(loc.where(tyre.materials_file().empty() ? "materials" : "materials_file"),
             std::string("no material for region '") + region_name(static_cast<Region>(k)) + "'");
  return out;
}

void check_region(const RegionEntry& e, cosim::ValidationReport& r) {
  const auto& m = e.material;
  const auto& w = *e.where;
  if (m.has_rubber()) {
    const auto loc = w.child("rubber");
    if (!(m.rubber().density_kg_per_m3() > 0)) r.fail(loc.where("density_kg_per_m3"), "must be > 0");
    if (!(m.rubber().c10_pa() > 0)) r.fail(loc.where("C10_Pa"), "must be > 0 (initial shear modulus 2 C10)");
    if (m.rubber().bulk_to_shear_ratio() < 0) r.fail(loc.where("bulk_to_shear_ratio"), "must be >= 0");
  } else if (m.has_elastic()) {
    const auto loc = w.child("elastic");
    if (!(m.elastic().density_kg_per_m3() > 0)) r.fail(loc.where("density_kg_per_m3"), "must be > 0");
    if (!(m.elastic().youngs_modulus_pa() > 0)) r.fail(loc.where("youngs_modulus_Pa"), "must be > 0");
    if (!(m.elastic().poisson_ratio() >= 0 && m.elastic().poisson_ratio() < 0.5))
      r.fail(loc.where("poisson_ratio"), "must be in [0, 0.5) (got " + num(m.elastic().poisson_ratio()) + ")");
  } else {
    r.fail(w.where("region"), "region '" + m.region() + "' needs `rubber` or `elastic`");
  }
  if (m.has_rebar()) {
    const auto loc = w.child("rebar");
    const auto& b = m.rebar();
    if (!(b.cross_section_area_m2() > 0)) r.fail(loc.where("cross_section_area_m2"), "must be > 0");
    if (!(b.spacing_m() > 0)) r.fail(loc.where("spacing_m"), "must be > 0");
    if (!(b.youngs_modulus_pa() > 0)) r.fail(loc.where("youngs_modulus_Pa"), "must be > 0");
    if (!(b.density_kg_per_m3() >= 0)) r.fail(loc.where("density_kg_per_m3"), "must be >= 0");
    if (!(std::fabs(b.orientation_deg()) <= 90)) r.fail(loc.where("orientation_deg"), "must be in [-90, 90]");
  }
}

TreadVariant variant_of(sc::TreadVariantKind k) {
  switch (k) {
    case sc::RIB: return TreadVariant::rib;
    case sc::BLOCK: return TreadVariant::block;
    case sc::BLOCK_SIPES: return TreadVariant::block;  // the sipes are the coupler's friction (scene.proto)
    case sc::BLOCK_SIPES_MESHED: return TreadVariant::block_sipes;
    default: return TreadVariant::smooth;
  }
}

}  // namespace

void validate_tyre_scene(const cosim::LoadedScene& loaded, cosim::ValidationReport& r) {
  const sc::Scene& scene = loaded.message;
  if (!scene.has_tyre()) return;
  const auto& t = scene.tyre();
  const auto loc = loaded.locator().child("tyre");
  if (t.size().empty() == t.cross_section_inp().empty())
    r.fail(loc.where(t.size().empty() ? "size" : "cross_section_inp"),
           "give either a size designation (e.g. \"235/75R15\") or an Abaqus cross_section_inp, not both");
  if (!t.size().empty()) {
    try {
      parse_tyre_size(t.size());
    } catch (const cosim::Error& e) {
      r.fail(loc.where("size"), e.what());
    }
  }
  const auto& mesh = t.mesh();
  if (!(mesh.element_size_m() > 0)) r.fail(loc.child("mesh").where("element_size_m"), "must be > 0");
  if (mesh.tread_layers() < 1) r.fail(loc.child("mesh").where("tread_layers"), "must be >= 1");
  const auto& p = t.tread();
  const auto tl = loc.child("tread");
  if (p.variant() == sc::TREAD_UNSET) r.fail(tl.where("variant"), "choose SMOOTH, RIB, BLOCK, BLOCK_SIPES or BLOCK_SIPES_MESHED");
  if (!(p.groove_depth_m() > 0)) r.fail(tl.where("groove_depth_m"), "must be > 0");
  if (!(p.tread_base_m() > 0)) r.fail(tl.where("tread_base_m"), "must be > 0");
  if (p.pitch_count() < 1) r.fail(tl.where("pitch_count"), "must be >= 1");
  if (p.elements_per_pitch() < 1) r.fail(tl.where("elements_per_pitch"), "must be >= 1");
  if (p.pitch_count() * p.elements_per_pitch() < 24)
    r.fail(tl.where("elements_per_pitch"), "pitch_count * elements_per_pitch must be >= 24 divisions");
  if (p.variant() != sc::SMOOTH && p.variant() != sc::TREAD_UNSET) {
    if (p.circumferential_groove_y_m_size() == 0)
      r.fail(tl.where("circumferential_groove_y_m"), "a patterned tread needs circumferential grooves");
    if (!(p.circumferential_groove_width_m() > 0)) r.fail(tl.where("circumferential_groove_width_m"), "must be > 0");
  }
  if (p.variant() == sc::BLOCK || p.variant() == sc::BLOCK_SIPES || p.variant() == sc::BLOCK_SIPES_MESHED)
    if (!(p.lateral_groove_width_m() > 0)) r.fail(tl.where("lateral_groove_width_m"), "must be > 0");
  if (p.variant() == sc::BLOCK_SIPES)
    for (const auto& [field, given] : {std::pair<const char*, bool>{"sipes_per_block", p.sipes_per_block() != 0},
                                       {"sipe_width_m", p.sipe_width_m() != 0},
                                       {"sipe_depth_m", p.sipe_depth_m() != 0}})
      if (given)
        r.fail(tl.where(field), "BLOCK_SIPES is the thesis's block tread with the sipes' equivalent friction "
                                "on its top and no slits in the mesh (section 6.1); cut slits with "
                                "variant: BLOCK_SIPES_MESHED");
  if (p.variant() == sc::BLOCK_SIPES_MESHED) {
    if (p.sipes_per_block() < 1) r.fail(tl.where("sipes_per_block"), "must be >= 1");
    if (!(p.sipe_depth_m() > 0 && p.sipe_depth_m() <= p.groove_depth_m()))
      r.fail(tl.where("sipe_depth_m"), "must be in (0, groove_depth_m]");
    if (!(p.sipe_width_m() > 0)) r.fail(tl.where("sipe_width_m"), "must be > 0");
  }
  if (t.bulk_to_shear_ratio() != 0 && !(t.bulk_to_shear_ratio() >= 2))
    r.fail(loc.where("bulk_to_shear_ratio"), "K0/mu0 must be >= 2 (rubber is nearly incompressible)");
  if (t.hourglass_coefficient() < 0 || t.hourglass_coefficient() > 1)
    r.fail(loc.where("hourglass_coefficient"), "must be in [0, 1]");
  if (t.inflation_pressure_pa() < 0) r.fail(loc.where("inflation_pressure_Pa"), "must be >= 0");
  if (t.mass_scaling_target_dt_s() < 0) r.fail(loc.where("mass_scaling_target_dt_s"), "must be >= 0");
  const auto rl = loc.child("rim");
  if (!(t.rim().mass_kg() > 0)) r.fail(rl.where("mass_kg"), "must be > 0");
  if (!(t.rim().spin_inertia_kg_m2() > 0)) r.fail(rl.where("spin_inertia_kg_m2"), "must be > 0");
  if (t.rim().wheel_load_n() < 0) r.fail(rl.where("wheel_load_N"), "must be >= 0 (it presses downwards)");
  const auto st = loc.child("stages");
  for (const char* f : {"transfer_check_s", "loading_s", "rolling_s", "average_last_s", "loading_damping_per_s",
                        "loading_rest_tolerance", "loading_rest_speed_m_per_s", "loading_rest_hold_s"}) {
    const auto* field = sc::TyreStages::descriptor()->FindFieldByName(f);
    if (t.stages().GetReflection()->GetDouble(t.stages(), field) < 0) r.fail(st.where(f), "must be >= 0");
  }
  if (t.stages().loading_s() > 0 || t.stages().rolling_s() > 0) {
    if (!t.has_road()) r.fail(loc.where("road"), "loading and rolling stages need a road");
    if (!(t.rim().wheel_load_n() > 0)) r.fail(rl.where("wheel_load_N"), "loading needs a wheel load > 0");
  }
  if (t.has_road() && t.road().friction_coefficient() < 0)
    r.fail(loc.child("road").where("friction_coefficient"), "must be >= 0");
  if (t.stages().rolling_s() > 0 && t.rim().forward_speed_m_per_s() == 0 &&
      t.rim().spin_case() == sc::RimSpec::SPIN_NOT_SET)
    r.fail(rl.where("forward_speed_m_per_s"), "a rolling stage needs a forward speed, a spin or a torque");
  if (!t.cross_section_inp().empty() && !std::ifstream(resolve(loaded.file, t.cross_section_inp())))
    r.fail(loc.where("cross_section_inp"), "cannot open '" + resolve(loaded.file, t.cross_section_inp()) + "'");
  try {
    const Materials mats = collect_materials(loaded, r);
    for (const auto& e : mats.regions)
      if (e) check_region(*e, r);
  } catch (const cosim::Error& e) {
    r.fail(loc.where("materials_file"), e.what());
  }
}

TyreSetup tyre_setup(const cosim::LoadedScene& loaded) {
  const auto& t = loaded.message.tyre();
  TyreSetup s;
  if (!t.size().empty()) s.size = parse_tyre_size(t.size()), s.size_designation = t.size();
  s.cross_section_inp = resolve(loaded.file, t.cross_section_inp());
  s.mesh.target_element_size_m = t.mesh().element_size_m();
  s.mesh.tread_layers = t.mesh().tread_layers();
  const auto& p = t.tread();
  s.pattern.variant = variant_of(p.variant());
  s.pattern.tread_width_m = p.tread_width_m();
  s.pattern.groove_depth_m = p.groove_depth_m();
  s.pattern.tread_base_m = p.tread_base_m();
  s.pattern.circumferential_groove_y_m.assign(p.circumferential_groove_y_m().begin(),
                                              p.circumferential_groove_y_m().end());
  s.pattern.circumferential_groove_width_m = p.circumferential_groove_width_m();
  s.pattern.pitch_count = p.pitch_count();
  s.pattern.lateral_groove_width_m = p.lateral_groove_width_m();
  s.pattern.sipes_per_block = p.sipes_per_block();
  s.pattern.sipe_width_m = p.sipe_width_m();
  s.pattern.sipe_depth_m = p.sipe_depth_m();
  s.pattern.elements_per_pitch = p.elements_per_pitch();
  s.bulk_to_shear_ratio = t.bulk_to_shear_ratio();
  s.bead_tied_to_rim = !t.rim().deformable_bead();
  cosim::ValidationReport report;
  const Materials mats = collect_materials(loaded, report);
  report.throw_if_failed();
  s.materials_source = mats.source;
  s.materials.hourglass_coefficient = t.hourglass_coefficient();
  for (int k = 0; k < kRegionCount; ++k) {
    const auto& m = mats.regions[k]->material;
    SolidMaterial& solid = s.materials.solid[k];
    if (m.has_rubber()) {
      solid.kind = SolidMaterial::Kind::yeoh;
      solid.yeoh.C10_Pa = m.rubber().c10_pa();
      solid.yeoh.C20_Pa = m.rubber().c20_pa();
      solid.yeoh.C30_Pa = m.rubber().c30_pa();
      solid.yeoh.density_kg_per_m3 = m.rubber().density_kg_per_m3();
      const double ratio = rubber_bulk_to_shear_ratio(m.rubber(), s.bulk_to_shear_ratio);
      solid.yeoh.bulk_modulus_Pa = ratio * 2.0 * solid.yeoh.C10_Pa;
    } else {
      solid.kind = SolidMaterial::Kind::elastic;
      solid.elastic.youngs_modulus_Pa = m.elastic().youngs_modulus_pa();
      solid.elastic.poisson_ratio = m.elastic().poisson_ratio();
      solid.elastic.density_kg_per_m3 = m.elastic().density_kg_per_m3();
    }
    if (m.has_rebar()) {
      RebarLayer& b = s.materials.rebar[k];
      b.area_m2 = m.rebar().cross_section_area_m2();
      b.spacing_m = m.rebar().spacing_m();
      b.angle_rad = m.rebar().orientation_deg() * kPi / 180.0;
      b.youngs_modulus_Pa = m.rebar().youngs_modulus_pa();
      b.density_kg_per_m3 = m.rebar().density_kg_per_m3();
    }
  }
  return s;
}

CrossSection make_section(const TyreSetup& setup) {
  CrossSection section =
      !setup.cross_section_inp.empty()
          ? import_abaqus_cross_section(setup.cross_section_inp, setup.pattern.tread_width_m > 0
                                                                     ? 0.5 * setup.pattern.tread_width_m
                                                                     : 0.4 * setup.size.section_width_m)
          : make_cross_section(setup.size, setup.pattern, setup.mesh);
  if (setup.bead_tied_to_rim) tie_region_to_rim(section, Region::bead);
  return section;
}

double time_step_safety(const sc::Scene& scene) { return scene.time().cfl() > 0 ? scene.time().cfl() : 0.8; }

double rubber_bulk_to_shear_ratio(const sc::YeohRubberMaterial& rubber, double body_ratio) {
  return rubber.bulk_to_shear_ratio() > 0 ? rubber.bulk_to_shear_ratio() : body_ratio;
}

double averaging_window_s(const sc::TyreStages& st) {
  return st.average_last_s() > 0 ? st.average_last_s() : 0.5 * st.rolling_s();
}

}  // namespace tyre_fe
