// Scenario YAML, the world sections: surface materials and regions, the label image, and
// the dynamic obstacles with their paths.

#include "pgmcl/map_io/map_io.hpp"
#include "scenario_parser.hpp"

namespace pgmcl::io::detail::scenario {

void ScenarioParser::read_surfaces(YamlMap m, sims::SurfaceLayout& s) {
  m.text("default", s.default_material);
  note("SurfaceLayout.default_material", m, "default");
  note("SurfaceLayout.materials", m, "materials");
  for (const auto& [node, field] : m.sequence("materials")) {
    YamlMap e(m.file(), node, field, m.line("materials"));
    std::string name;
    if (!e.text("name", name)) e.fail("name", "missing required key");
    sims::SurfaceMaterial* mat = nullptr;
    for (auto& known : s.materials) {
      if (known.name == name) mat = &known;
    }
    if (mat == nullptr) {
      s.materials.push_back(sims::SurfaceMaterial{name, {}, false});
      mat = &s.materials.back();
    }
    e.number("sigma_normal", mat->sigma.sigma_normal);
    e.number("sigma_45", mat->sigma.sigma_45);
    e.number("grazing_limit", mat->sigma.grazing_limit);
    e.boolean("specular", mat->specular);
    e.finish();
    checked(e, [&] { mat->sigma.validate(); });
  }
  if (m.text("labels", labels_path_)) {
    labels_path_ = resolve(labels_path_);
    labels_line_ = m.line("labels");
    note("SurfaceLayout.labels", m, "labels");
  }
  const std::size_t regions_line = m.line("regions");
  const auto regions = m.sequence("regions");
  for (std::size_t i = 0; i < regions.size(); ++i) {
    YamlMap r(m.file(), regions[i].first, regions[i].second, regions_line);
    sims::SurfaceRegion region;
    r.text("material", region.material);
    const auto lo = detail::yaml_xy(m.file(), r.require("min"), r.field("min"), r.line("min"));
    const auto hi = detail::yaml_xy(m.file(), r.require("max"), r.field("max"), r.line("max"));
    region.x_min = lo.first;
    region.y_min = lo.second;
    region.x_max = hi.first;
    region.y_max = hi.second;
    if (region.material.empty()) r.fail("material", "missing required key");
    if (!(region.x_min <= region.x_max && region.y_min <= region.y_max)) {
      r.fail("max", "must not be below min in x or y");
    }
    r.finish();
    const std::string sims_field = "SurfaceLayout.regions[" + std::to_string(i) + "]";
    note_map(sims_field, r);
    note(sims_field + ".material", r, "material");
    s.regions.push_back(region);
  }
  m.finish();
}

void ScenarioParser::read_path(YamlMap m, sims::ObstaclePath& p) {
  const std::size_t line = m.line("waypoints");
  for (const auto& [node, field] : m.sequence("waypoints")) {
    const auto xy = detail::yaml_xy(m.file(), node, field, line);
    p.waypoints.push_back({xy.first, xy.second});
  }
  if (p.waypoints.empty()) m.fail("waypoints", "need at least one [x, y] point");
  m.number("speed", p.speed);
  m.number("start_offset", p.start_offset);
  m.finish();
  checked(m, [&] { p.validate(m.path()); });
}

void ScenarioParser::read_obstacles(YamlMap m, sims::Scenario& sc) {
  const auto discs = m.sequence("discs");
  for (std::size_t i = 0; i < discs.size(); ++i) {
    YamlMap d(m.file(), discs[i].first, discs[i].second, m.line("discs"));
    sims::DiscObstacle disc;
    d.number("radius", disc.radius);
    if (!(disc.radius > 0.0)) d.fail("radius", "must be > 0 (m)");
    d.text("material", disc.material);
    read_path(d.child("path"), disc.path);
    d.finish();
    const std::string f = "Scenario.discs[" + std::to_string(i) + "]";
    note_map(f, d);
    note(f + ".material", d, "material");
    sc.discs.push_back(std::move(disc));
  }
  const auto boxes = m.sequence("boxes");
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    YamlMap b(m.file(), boxes[i].first, boxes[i].second, m.line("boxes"));
    sims::BoxObstacle box;
    b.number("half_length", box.half_length);
    b.number("half_width", box.half_width);
    if (!(box.half_length > 0.0)) b.fail("half_length", "must be > 0 (m)");
    if (!(box.half_width > 0.0)) b.fail("half_width", "must be > 0 (m)");
    b.number("yaw", box.yaw);
    b.text("material", box.material);
    read_path(b.child("path"), box.path);
    b.finish();
    const std::string f = "Scenario.boxes[" + std::to_string(i) + "]";
    note_map(f, b);
    note(f + ".material", b, "material");
    sc.boxes.push_back(std::move(box));
  }
  m.finish();
}

void ScenarioParser::load_labels(const maps::OccupancyGrid& map, sims::SurfaceLayout& s) const {
  if (labels_path_.empty()) return;
  maps::MapMetadata meta;
  meta.resolution = map.resolution();
  meta.origin = map.origin();
  meta.mode = maps::MapMode::kRaw;  // pixel value v in 0..100 is kept as is, else -1
  maps::OccupancyGrid img;
  try {
    img = maps::load_map_image(labels_path_, meta);
  } catch (const std::exception& e) {
    throw FormatError(path_, labels_line_, "surfaces.labels", e.what());
  }
  if (img.width() != map.width() || img.height() != map.height()) {
    throw FormatError(path_, labels_line_, "surfaces.labels",
                      "label image is " + std::to_string(img.width()) + "x" +
                          std::to_string(img.height()) + ", the map " +
                          std::to_string(map.width()) + "x" + std::to_string(map.height()));
  }
  s.labels.resize(img.size());
  for (std::size_t i = 0; i < img.size(); ++i) {
    const std::int8_t v = img.cells()[i];
    s.labels[i] = v < 0 ? sims::SurfaceLayout::kNoLabel : static_cast<std::uint8_t>(v);
  }
}

}  // namespace pgmcl::io::detail::scenario
