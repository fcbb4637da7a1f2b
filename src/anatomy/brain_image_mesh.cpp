// SPDX-License-Identifier: GPL-3.0-or-later
#include "anatomy/brain_image_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "anatomy/image_mesher.hpp"
#include "anatomy/image_volume.hpp"
#include "anatomy/voxel_mask.hpp"
#include "common/did_you_mean.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "mesh/msh_writer.hpp"
#include "mesh/node_count_search.hpp"
#include "mesh/quality_smoothing.hpp"

namespace roifem::anatomy {

namespace {

constexpr const char* colin27_dir = "/usr/share/mricron/templates";

void validate(const BrainImageOptions& o) {
  if (o.target_nodes < 200) throw InputError("--nodes " + std::to_string(o.target_nodes) + ": at least 200 nodes are needed");
  if (o.target_nodes > 1'000'000) throw InputError("--nodes " + std::to_string(o.target_nodes) + ": at most 1e6 nodes");
  if (!(o.tolerance > 0 && o.tolerance < 0.5)) throw InputError("--tolerance must lie in (0, 50) percent");
  if (!(o.cut_height_mm >= 0)) throw InputError("--cut-mm must not be negative");
  if (o.opening) {
    const auto& s = *o.opening;
    if (!(s.width_mm > 0 && s.length_mm > 0 && s.depth_mm > 0))
      throw InputError("--opening: width, length and depth must be positive");
  }
  std::set<std::string> names;
  for (const auto& r : o.regions) {
    if (!names.insert(r.name).second) throw InputError("--region " + r.name + " is given twice");
    for (const char* taken : {"brain", "surface", "brainstem_cut", "grey_matter", "white_matter", "csf", "opening_left",
                              "opening_right", "opening_floor"})
      if (r.name == taken) throw InputError("--region " + r.text + ": '" + r.name + "' names a set the mesher writes itself");
    if (r.kind == RegionSpec::Kind::label && o.atlas.empty())
      throw InputError("--region " + r.text + ": a label region needs --atlas (the label image)");
  }
}

/// Otsu's threshold between two classes of the tissue's intensities (256 bins).
double otsu_threshold(const std::vector<float>& values) {
  const auto [lo_it, hi_it] = std::minmax_element(values.begin(), values.end());
  const double lo = *lo_it, hi = *hi_it;
  if (!(hi > lo)) return 0;
  std::array<double, 256> histogram{};
  for (float v : values) histogram[std::min<std::size_t>(255, static_cast<std::size_t>((v - lo) / (hi - lo) * 256))] += 1;
  double total = 0, weighted = 0;
  for (std::size_t b = 0; b < 256; ++b) {
    total += histogram[b];
    weighted += static_cast<double>(b) * histogram[b];
  }
  double below = 0, below_weighted = 0, best = -1;
  std::size_t best_bin = 0;
  for (std::size_t b = 0; b < 255; ++b) {
    below += histogram[b];
    below_weighted += static_cast<double>(b) * histogram[b];
    if (below == 0 || below == total) continue;
    const double m0 = below_weighted / below, m1 = (weighted - below_weighted) / (total - below);
    const double between = below * (total - below) * (m0 - m1) * (m0 - m1);
    if (between > best) {
      best = between;
      best_bin = b;
    }
  }
  return lo + (static_cast<double>(best_bin) + 1) / 256 * (hi - lo);
}

/// The level whose superlevel set holds `volume_mm3` on the grid (voxels above it, counted whole):
/// the blurred mask's level with the mask's own volume. Kept within [0.25, 0.75], where the
/// level set still follows the mask's boundary.
double level_for_volume(const ImageVolume& grid, double volume_mm3) {
  std::vector<float> values;
  for (float v : grid.values)
    if (v > 0.01f) values.push_back(v);
  const auto keep = static_cast<std::size_t>(std::lround(volume_mm3 / grid.voxel_volume_mm3()));
  if (keep == 0 || keep >= values.size()) return 0.5;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(keep), values.end(), std::greater<>());
  return std::clamp(static_cast<double>(values[keep]), 0.25, 0.75);
}

/// The opening's box in world mm: its top is the brain's highest point over the footprint.
std::pair<Eigen::Vector3d, Eigen::Vector3d> opening_box(const ImageVolume& mask, const SurgicalOpening& s) {
  const double x0 = s.centre_x_mm - s.width_mm / 2, x1 = s.centre_x_mm + s.width_mm / 2;
  const double y0 = s.centre_y_mm - s.length_mm / 2, y1 = s.centre_y_mm + s.length_mm / 2;
  double top = -std::numeric_limits<double>::infinity();
  const auto [nx, ny, nz] = mask.dims;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (mask.at(i, j, k) <= 0) continue;
        const Eigen::Vector3d x = mask.to_mm(Eigen::Vector3d(i, j, k));
        if (x.x() >= x0 && x.x() <= x1 && x.y() >= y0 && x.y() <= y1) top = std::max(top, x.z());
      }
  if (!std::isfinite(top))
    throw InputError("--opening " + std::to_string(s.centre_x_mm) + "," + std::to_string(s.centre_y_mm) +
                     ": no brain lies under the opening's footprint (x, y in mm of the image's space)");
  return {Eigen::Vector3d(x0, y0, top - s.depth_mm), Eigen::Vector3d(x1, y1, top + 100)};
}

/// Clears the grid's voxels below the cut plane and inside the opening: applied after the blur,
/// so that both faces stay sharp at any blur.
void cut_and_carve(ImageVolume& grey, double cut_z, const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& box) {
  const auto [nx, ny, nz] = grey.dims;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Eigen::Vector3d x = grey.to_mm(Eigen::Vector3d(i, j, k));
        const bool carved = box && (x.array() >= box->first.array()).all() && (x.array() <= box->second.array()).all();
        if (x.z() < cut_z || carved) grey.values[grey.index(i, j, k)] = 0;
      }
}

/// Trilinear interpolation of the grid at a point in world mm (0 outside).
double interpolate(const ImageVolume& grid, const Eigen::Vector3d& mm_point) {
  const Eigen::Vector3d p = grid.to_index(mm_point);
  const int i = static_cast<int>(std::floor(p.x())), j = static_cast<int>(std::floor(p.y())),
            k = static_cast<int>(std::floor(p.z()));
  const double fx = p.x() - i, fy = p.y() - j, fz = p.z() - k;
  double value = 0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    if (!grid.inside(i + di, j + dj, k + dk)) continue;
    value += (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz) * grid.at(i + di, j + dj, k + dk);
  }
  return value;
}

/// Newton steps along the gradient onto {grid = iso}: where a boundary node may slide.
Eigen::Vector3d project_to_level_set(const ImageVolume& grid, double iso, Eigen::Vector3d x) {
  const double h = 0.25 * grid.spacing_mm().minCoeff();
  for (int iteration = 0; iteration < 8; ++iteration) {
    const double f = interpolate(grid, x) - iso;
    Eigen::Vector3d gradient;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[a] = h;
      gradient[a] = (interpolate(grid, x + e) - interpolate(grid, x - e)) / (2 * h);
    }
    const double g2 = gradient.squaredNorm();
    if (g2 < 1e-12) break;
    const Eigen::Vector3d step = f / g2 * gradient;
    x -= step;
    if (step.norm() < 1e-6) break;
  }
  return x;
}

struct Face {
  mesh::Triangle nodes;
  Eigen::Vector3d centre, normal;  // unit outward normal
};

std::vector<Face> boundary(const mesh::TetMesh& m) {
  std::vector<Face> faces;
  for (const auto& t : mesh::boundary_faces(m)) {
    Face f{t, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    const Eigen::Vector3d a = m.node(t[0]) / mm, b = m.node(t[1]) / mm, c = m.node(t[2]) / mm;
    f.centre = (a + b + c) / 3;
    f.normal = (b - a).cross(c - a).normalized();
    faces.push_back(f);
  }
  return faces;
}

void add_surface_set(mesh::TetMesh& m, const std::string& name, const std::vector<Face>& faces, const std::vector<bool>& chosen) {
  mesh::NamedSet set;
  set.dim = 2;
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (chosen[f]) {
      set.triangles.push_back(faces[f].nodes);
      for (int n : faces[f].nodes) set.nodes.push_back(n);
    }
  std::sort(set.nodes.begin(), set.nodes.end());
  set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
  m.sets[name] = std::move(set);
}

void add_volume_set(mesh::TetMesh& m, const std::string& name, std::vector<int> tets) {
  mesh::NamedSet set;
  set.dim = 3;
  for (int e : tets)
    for (int n : m.tets[static_cast<std::size_t>(e)]) set.nodes.push_back(n);
  std::sort(set.nodes.begin(), set.nodes.end());
  set.nodes.erase(std::unique(set.nodes.begin(), set.nodes.end()), set.nodes.end());
  set.tets = std::move(tets);
  m.sets[name] = std::move(set);
}

/// The atlas label under a boundary face: sampled 1.5 mm inside it, then deeper up to 6 mm
/// (the surface of a smoothed mesh can lie just outside the atlas's labelled voxels).
int label_under(const ImageVolume& atlas, const Face& f) {
  for (double depth = 1.5; depth <= 6.0; depth += 1.5) {
    const float v = atlas.nearest(f.centre - depth * f.normal);
    if (v > 0) return static_cast<int>(std::lround(v));
  }
  return 0;
}

/// The message for a label that is neither a number nor a name in the atlas's table, with the
/// name it may be a typo of (case aside).
std::string unknown_label(const RegionSpec& r, const std::string& label, const std::map<std::string, int>& table) {
  std::string known;
  std::vector<std::string> names;
  for (const auto& [name, number] : table) {
    if (names.size() < 6) known += (known.empty() ? "" : ", ") + name;
    names.push_back(name);
  }
  std::string hint;
  for (const auto& name : names)
    if (name.size() == label.size() && std::equal(name.begin(), name.end(), label.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
        }))
      hint = " (did you mean '" + name + "'?)";
  if (hint.empty()) hint = did_you_mean(label, names);
  return "--region " + r.text + ": '" + label + "' is neither a label number nor a name in the atlas's table" + hint + " (" +
         known + ", ... " + std::to_string(names.size()) + " in all)";
}

/// The label numbers a --region NAME=label:... names, by number or by the atlas's table: InputError
/// for a name not in the table or a number it does not list.
std::set<int> region_labels(const RegionSpec& r, const std::map<std::string, int>& table) {
  std::set<int> labels;
  for (const auto& l : r.labels) {
    auto it = table.find(l);
    if (it != table.end()) {
      labels.insert(it->second);
      continue;
    }
    std::optional<int> number;
    try {
      std::size_t used = 0;
      const int n = std::stoi(l, &used);
      if (used == l.size()) number = n;
    } catch (const std::exception&) {
    }
    if (!number) throw InputError(unknown_label(r, l, table));
    const bool listed = std::any_of(table.begin(), table.end(), [&](const auto& entry) { return entry.second == *number; });
    if (!listed && !table.empty()) {
      const auto [low, high] =
          std::minmax_element(table.begin(), table.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
      throw InputError("--region " + r.text + ": the atlas's table has no label " + std::to_string(*number) + " (its " +
                       std::to_string(table.size()) + " labels run from " + std::to_string(low->second) + " to " +
                       std::to_string(high->second) + ")");
    }
    labels.insert(*number);
  }
  return labels;
}

/// The atlas's table of label names beside it (aal.nii.gz -> aal.nii.txt); empty where there is none.
std::map<std::string, int> atlas_table(const std::filesystem::path& atlas) {
  std::filesystem::path table_file = atlas;
  table_file.replace_extension();  // aal.nii.gz -> aal.nii
  if (table_file.extension() != ".nii") table_file = atlas;
  table_file += ".txt";
  return std::filesystem::exists(table_file) ? read_label_table(table_file) : std::map<std::string, int>{};
}

std::vector<bool> region_faces(const RegionSpec& r, const std::vector<Face>& faces, const ImageVolume* atlas,
                               const std::map<std::string, int>& table) {
  std::vector<bool> chosen(faces.size(), false);
  if (r.kind == RegionSpec::Kind::below) {
    for (std::size_t f = 0; f < faces.size(); ++f) chosen[f] = faces[f].centre.z() < r.below_z_mm;
    if (std::find(chosen.begin(), chosen.end(), true) == chosen.end())
      throw InputError("--region " + r.text + ": no boundary triangle lies below that height (the brain's bottom is higher)");
    return chosen;
  }
  if (r.kind == RegionSpec::Kind::sphere) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const double d = (faces[f].centre - r.centre_mm).norm();
      nearest = std::min(nearest, d);
      chosen[f] = d <= r.radius_mm;
    }
    if (std::find(chosen.begin(), chosen.end(), true) == chosen.end()) {
      char text[160];
      std::snprintf(text, sizeof text,
                    ": no boundary triangle lies within %.3g mm of the point; the brain's surface is %.3g mm from it",
                    r.radius_mm, nearest);
      throw InputError("--region " + r.text + text + " (is the point outside the brain, or in another space than the image's?)");
    }
    return chosen;
  }
  const std::set<int> labels = region_labels(r, table);
  for (std::size_t f = 0; f < faces.size(); ++f) chosen[f] = labels.count(label_under(*atlas, faces[f])) > 0;
  if (std::find(chosen.begin(), chosen.end(), true) == chosen.end())
    throw InputError("--region " + r.text + ": no boundary triangle lies over that atlas label (a deep structure?)");
  return chosen;
}

void name_sets(mesh::TetMesh& m, const BrainImageOptions& o, const ImageVolume& image, const ImageVolume& tissue_mask,
               double cut_z, double band_mm, const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& box,
               BrainImageMesh& result) {
  std::vector<int> all(m.tets.size());
  for (std::size_t e = 0; e < all.size(); ++e) all[e] = static_cast<int>(e);
  add_volume_set(m, "brain", all);

  if (o.tissues) {
    std::vector<float> tissue;
    for (std::size_t n = 0; n < image.size(); ++n)
      if (image.values[n] > o.threshold) tissue.push_back(image.values[n]);
    std::set<float> levels(tissue.begin(),
                           tissue.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(tissue.size(), 100000)));
    if (levels.size() > 2) {  // a grey image, not a binary mask
      result.tissue_threshold = otsu_threshold(tissue);
      std::vector<int> grey, white, csf;
      for (std::size_t e = 0; e < m.tets.size(); ++e) {
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        for (int n : m.tets[e]) centre += m.node(n) / mm / 4;
        const float value = image.nearest(centre);
        const bool in_tissue = tissue_mask.nearest(centre) > 0 && value > o.threshold;
        (!in_tissue ? csf : value > result.tissue_threshold ? white : grey).push_back(static_cast<int>(e));
      }
      add_volume_set(m, "grey_matter", grey);
      add_volume_set(m, "white_matter", white);
      if (!csf.empty()) add_volume_set(m, "csf", csf);
    }
  }

  const std::vector<Face> faces = boundary(m);
  add_surface_set(m, "surface", faces, std::vector<bool>(faces.size(), true));
  std::vector<bool> cut(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) cut[f] = faces[f].normal.z() < -0.8 && faces[f].centre.z() < cut_z + band_mm;
  if (o.cut_height_mm > 0) {
    if (std::find(cut.begin(), cut.end(), true) == cut.end())
      throw ModelError(image.source + ": the bottom cut at z = " + std::to_string(cut_z) +
                       " mm left no flat face to hold the brain by (a larger --cut-mm?)");
    add_surface_set(m, "brainstem_cut", faces, cut);
  }
  if (box) {
    const Eigen::Vector3d lo = box->first.array() - band_mm, hi = box->second.array() + band_mm;
    const double centre_x = 0.5 * (box->first.x() + box->second.x());
    std::vector<bool> left(faces.size()), right(faces.size()), floor(faces.size());
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto& face = faces[f];
      if (!((face.centre.array() >= lo.array()).all() && (face.centre.array() <= hi.array()).all())) continue;
      left[f] = face.normal.x() > 0.7 && face.centre.x() < centre_x;
      right[f] = face.normal.x() < -0.7 && face.centre.x() > centre_x;
      floor[f] = face.normal.z() > 0.7 && face.centre.z() < box->first.z() + band_mm;
    }
    for (const auto& [name, chosen] : {std::pair{"opening_left", &left}, {"opening_right", &right}, {"opening_floor", &floor}}) {
      if (std::find(chosen->begin(), chosen->end(), true) == chosen->end())
        throw ModelError(std::string("--opening: the mesh has no face on ") + name +
                         " (too coarse a mesh for the opening? more --nodes)");
      add_surface_set(m, name, faces, *chosen);
    }
  }
  std::optional<ImageVolume> atlas;
  std::map<std::string, int> table;
  for (const auto& r : o.regions) {
    if (r.kind == RegionSpec::Kind::label && !atlas) {
      atlas = read_nifti(o.atlas);
      table = atlas_table(o.atlas);
    }
    add_surface_set(m, r.name, faces, region_faces(r, faces, atlas ? &*atlas : nullptr, table));
  }
}

/// InputError, before CGAL sees it, for a mask too small for the nodes asked: N nodes take elements
/// of about h = cbrt(1.5 V / N), and one below two voxels follows no shape the image holds (CGAL's
/// search for initial points on the surface of a voxel or of nothing never ends).
void check_mask_holds_the_nodes(const BrainImageOptions& o, const ImageVolume& image, double volume_mm3) {
  const double voxel = image.spacing_mm().minCoeff();
  const double needed_mm3 = static_cast<double>(o.target_nodes) * std::pow(2 * voxel, 3) / 1.5;
  if (volume_mm3 >= needed_mm3) return;
  const std::string after = o.cut_height_mm > 0 || o.opening ? format(" after the bottom cut (--cut-mm %g)%s", o.cut_height_mm,
                                                                      o.opening ? " and the opening" : "")
                                                             : "";
  throw InputError(format(
      "%s: the mask holds %.4g mm^3 (%.0f voxels of %.3g mm^3)%s, and --nodes %lld needs at least %.4g mm^3 (elements of two "
      "voxels, %.3g mm, or larger): fewer --nodes%s",
      image.source.c_str(), volume_mm3, volume_mm3 / image.voxel_volume_mm3(), image.voxel_volume_mm3(), after.c_str(),
      static_cast<long long>(o.target_nodes), needed_mm3, 2 * voxel, o.cut_height_mm > 0 ? ", or a smaller --cut-mm" : ""));
}

}  // namespace

std::filesystem::path colin27_image() {
  const std::filesystem::path file = std::filesystem::path(colin27_dir) / "ch2better.nii.gz";
  return std::filesystem::exists(file) ? file : std::filesystem::path();
}

std::filesystem::path colin27_atlas() {
  const std::filesystem::path file = std::filesystem::path(colin27_dir) / "aal.nii.gz";
  return std::filesystem::exists(file) ? file : std::filesystem::path();
}

BrainImageMesh mesh_brain_image(const BrainImageOptions& o, const std::filesystem::path& output,
                                const std::function<void(const std::string&)>& progress) {
  validate(o);
  // A label the atlas's table does not hold is refused now, not after minutes of meshing.
  if (std::any_of(o.regions.begin(), o.regions.end(), [](const RegionSpec& r) { return r.kind == RegionSpec::Kind::label; })) {
    const auto table = atlas_table(o.atlas);
    for (const auto& r : o.regions)
      if (r.kind == RegionSpec::Kind::label) region_labels(r, table);
  }
  BrainImageMesh result;
  const ImageVolume image = read_nifti(o.image);
  MaskCleanup clean = clean_mask(image, o.threshold);
  result.dropped_pieces = clean.dropped_pieces;
  result.dropped_voxels = clean.dropped_voxels;
  result.filled_voxels = clean.filled_voxels;
  ImageVolume measured = clean.mask;  // the mask as meshed: cut and carved, at the image's resolution
  result.cut_plane_z_mm = o.cut_height_mm > 0 ? cut_bottom(measured, o.cut_height_mm) : -1e300;
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> box;
  if (o.opening) {
    box = opening_box(clean.mask, *o.opening);
    result.opening_centre_mm =
        Eigen::Vector3d(o.opening->centre_x_mm, o.opening->centre_y_mm, box->first.z() + o.opening->depth_mm / 2);
    if (o.opening->carved) carve_box(measured, box->first, box->second);
  }
  const auto carved = o.opening && o.opening->carved ? box : std::nullopt;
  result.mask_volume_mm3 = integral_mm3(measured);
  const double native = image.spacing_mm().minCoeff();
  check_mask_holds_the_nodes(o, image, result.mask_volume_mm3);

  // Node count against size: N ~ c V / h^3 with c from 1.3 (37k nodes) to 2 (2k) on Colin27; then a secant on
  // log N against log h within a bracket, as for the ellipsoid.
  const double target = static_cast<double>(o.target_nodes);
  mesh::NodeCountSearch search(target, std::cbrt(1.5 * result.mask_volume_mm3 / target), -2.6);
  std::map<std::pair<int, long>, ImageVolume> grids;  // (factor, sigma in um) -> blurred grid
  double iso = 0.5;                                   // the level meshed on that grid
  for (int attempt = 0; attempt < 10 && !search.stuck(); ++attempt) {
    const double h = search.size();
    // The working grid: voxels of about h/3 (never finer than the image's; at most 1/4 of the
    // opening's width, so its walls stay straight), blurred by sigma = h/3: it smooths what the
    // elements cannot follow (h/5 left 100k-node meshes with quality 0.07). A blur fills sulci
    // (the 0.5 level of h/3 at 2k nodes holds 2.3% more than the mask), so the mesher meshes the
    // level that keeps the mask's volume instead (level_for_volume).
    const double sigma = std::max(native, h / 3);
    double voxel = sigma;
    if (carved) voxel = std::min(voxel, o.opening->width_mm / 4);
    const int factor = std::max(1, static_cast<int>(std::floor(voxel / native + 1e-9)));
    const long sigma_key = std::lround(sigma * 10) * 100;  // blur quantized to 0.1 mm: reuse grids across attempts
    auto grid = grids.find({factor, sigma_key});
    if (grid == grids.end()) {
      ImageVolume grey = block_average(clean.mask, factor);
      grey = pad(grey, static_cast<int>(std::ceil(3 * (sigma_key / 1000.0) / (native * factor))) + 2);
      gaussian_blur(grey, sigma_key / 1000.0);
      cut_and_carve(grey, result.cut_plane_z_mm, carved);
      iso = level_for_volume(grey, result.mask_volume_mm3);
      grids.clear();
      grid = grids.emplace(std::pair{factor, sigma_key}, std::move(grey)).first;
    }
    ImageMeshSizes sizes;
    sizes.size_mm = h;
    sizes.distance_mm = h / 8;
    if (box) {  // the opening's walls (or the incision's box) in triangles of about its width, as the ellipsoid's
      sizes.refine_box_mm = box;
      sizes.refine_size_mm = std::min(h, std::max(o.opening->width_mm, h / 3));
    }
    RawTetMesh raw = mesh_image_level_set(grid->second, iso, sizes, o.seed);
    ++result.attempts;
    const auto n = static_cast<double>(raw.points_mm.cols());
    if (progress) {
      char line[200];
      std::snprintf(line, sizeof line, "meshing %d: size %.3f mm, working voxel %.2f mm, blur %.2f mm, level %.3f -> %.0f nodes",
                    result.attempts, h, native * factor, sigma_key / 1000.0, iso, n);
      progress(line);
    }
    if (search.record(n, o.tolerance)) {
      result.size_mm = h;
      result.working_voxel_mm = native * factor;
      result.blur_sigma_mm = sigma_key / 1000.0;
      result.mesh.nodes = raw.points_mm * mm;
      result.mesh.tets = std::move(raw.tets);
      break;
    }
  }
  if (result.size_mm == 0)
    throw InputError(o.image.string() + ": could not reach " + std::to_string(o.target_nodes) + " nodes within " +
                     std::to_string(o.tolerance * 100) + "% in " + std::to_string(result.attempts) + " meshings");
  const ImageVolume& level_set = grids.begin()->second;
  // Mesh_3 leaves a few slivers whose nodes all lie on the surface (quality 0.03-0.1): smooth the
  // poor tetrahedra's nodes (boundary nodes sliding on the level set), then remove the flat caps
  // left on the surface and smooth what stays below 0.1 with more freedom to turn the surface.
  // The return type is spelled out: deduced, it would be an Eigen expression of a dead temporary.
  const auto slide = [&](const Vec3& x) -> Vec3 { return project_to_level_set(level_set, iso, x / mm) * mm; };
  const mesh::SmoothingReport smoothing = mesh::smooth_poor_tetrahedra(result.mesh, 0.3, 8, slide);
  result.quality_min_meshed = smoothing.quality_min_before;
  if (smoothing.quality_min_after < 0.1) {
    result.caps_removed = mesh::remove_boundary_caps(result.mesh, 0.1);
    mesh::smooth_poor_tetrahedra(result.mesh, 0.1, 8, slide, 30);
  }
  result.mesh.source = output.empty() ? "<" + o.image.string() + ">" : output.string();
  name_sets(result.mesh, o, image, clean.mask, result.cut_plane_z_mm, std::max(1.0, result.working_voxel_mm) + 0.5, carved,
            result);
  if (!output.empty()) mesh::write_msh(result.mesh, output, mm);
  return result;
}

}  // namespace roifem::anatomy
