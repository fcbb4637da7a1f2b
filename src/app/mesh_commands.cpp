// SPDX-License-Identifier: GPL-3.0-or-later
// roifem mesh / roifem info
#include <cstdio>
#include <iostream>

#include "anatomy/brain_image_mesh.hpp"
#include "app/commands.hpp"
#include "common/errors.hpp"
#include "common/timer.hpp"
#include "common/types.hpp"
#include "mesh/brain_mesh.hpp"
#include "mesh/gmsh_reader.hpp"
#include "mesh/mesh_checks.hpp"

namespace roifem::app {

namespace {

/// "X,Y" or "X,Y,WIDTH,LENGTH,DEPTH" (mm) -> the opening carved into an image brain (or, for
/// `option` --incision, the box only refined).
anatomy::SurgicalOpening parse_opening(const std::vector<double>& v, const std::string& option = "--opening") {
  if (v.size() != 2 && v.size() != 5)
    throw InputError(option + ": give X,Y (mm; the slit's centre over the brain) or X,Y,WIDTH,LENGTH,DEPTH");
  anatomy::SurgicalOpening opening;
  opening.centre_x_mm = v[0];
  opening.centre_y_mm = v[1];
  if (v.size() == 5) {
    opening.width_mm = v[2];
    opening.length_mm = v[3];
    opening.depth_mm = v[4];
  }
  opening.carved = option == "--opening";
  return opening;
}

void mesh_image(anatomy::BrainImageOptions options, const std::vector<std::string>& regions, const std::vector<double>& opening,
                const std::vector<double>& incision, const std::string& out) {
  for (const auto& r : regions) options.regions.push_back(anatomy::parse_region(r));
  if (!opening.empty() && !incision.empty()) throw InputError("--opening and --incision: give one (a brain has one slit)");
  if (!opening.empty()) options.opening = parse_opening(opening);
  if (!incision.empty()) options.opening = parse_opening(incision, "--incision");
  Stopwatch clock;
  const auto result = anatomy::mesh_brain_image(options, out, [](const std::string& line) {
    std::printf("  %s\n", line.c_str());
    std::fflush(stdout);
  });
  const auto s = mesh::mesh_statistics(result.mesh);
  std::printf("wrote %s: %lld nodes, %lld tetrahedra from %s (size %.2f mm, %d meshings, %.1f s)\n", out.c_str(),
              static_cast<long long>(s.nodes), static_cast<long long>(s.tets), options.image.c_str(), result.size_mm,
              result.attempts, clock.seconds());
  std::printf(
      "volume %.1f cm^3 (the cleaned mask: %.1f cm^3, %+.2f%%), quality min %.3f (%.3f before smoothing%s), median %.3f\n",
      s.volume * 1e6, result.mask_volume_mm3 * 1e-3, 100 * (s.volume * 1e9 / result.mask_volume_mm3 - 1), s.quality_min,
      result.quality_min_meshed,
      result.caps_removed > 0 ? (", " + std::to_string(result.caps_removed) + " flat tetrahedra removed").c_str() : "",
      s.quality_median);
  std::printf("mask: %zu loose pieces (%zu voxels) dropped, %zu voxels of holes filled; bottom cut at z = %.1f mm\n",
              result.dropped_pieces, result.dropped_voxels, result.filled_voxels, result.cut_plane_z_mm);
  if (result.opening_centre_mm)
    std::printf("%s: centre (%.1f, %.1f, %.1f) mm (roifem paper --target-mm %.1f,%.1f,%.1f)\n",
                options.opening->carved ? "opening" : "incision (refined, not carved)", result.opening_centre_mm->x(),
                result.opening_centre_mm->y(), result.opening_centre_mm->z(), result.opening_centre_mm->x(),
                result.opening_centre_mm->y(), result.opening_centre_mm->z());
  for (const auto& [name, set] : result.mesh.sets)
    std::printf("  %-16s %dD  %6zu nodes  %6zu tetrahedra  %6zu triangles\n", name.c_str(), set.dim, set.nodes.size(),
                set.tets.size(), set.triangles.size());
}

}  // namespace

void add_mesh_command(CLI::App& app, Action& action) {
  struct Options {
    Index nodes = 800;
    std::string out;
    double tolerance = 3;
    double slit_refinement = 1;
    bool no_opening = false;
    std::string image;
    bool colin27 = false;
    anatomy::BrainImageOptions anatomy;
    std::vector<std::string> regions;
    std::vector<double> opening, incision;
  };
  auto opts = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("mesh",
                                 "Generate a brain mesh in millimetres: the simplified brain (ellipsoid 14 x 17 x 10 cm with a "
                                 "surgical opening, Gmsh), or a real brain from an image (--colin27 or --image, CGAL Mesh_3)");
  cmd->add_option("--nodes", opts->nodes, "Number of nodes wanted (e.g. 800, 5000, 20000, 100000, 300000)")
      ->capture_default_str();
  cmd->add_option("--out", opts->out, "Output mesh file (.msh, Gmsh 4.1 ASCII)")->required();
  cmd->add_option("--tolerance", opts->tolerance, "Allowed deviation from --nodes, in percent (images: at least 3)")
      ->capture_default_str();
  cmd->add_option(
         "--slit-refinement", opts->slit_refinement,
         "Ellipsoid only: element size at the opening's faces relative to the rest, graded back over 30 mm (1: uniform); "
         "with --no-opening, in the box the opening would take")
      ->capture_default_str();
  cmd->add_flag("--no-opening", opts->no_opening,
                "Ellipsoid only: a whole brain, no slit carved (a scenario's [[cut]] makes the incision; no opening_* sets)");
  auto* image = cmd->add_option("--image", opts->image,
                                "A brain image (NIfTI .nii or .nii.gz; skull-stripped, or a mask): mesh the voxels above "
                                "--threshold, largest piece, holes filled, cut flat at the bottom");
  auto* colin = cmd->add_flag("--colin27", opts->colin27,
                              "The Colin27 brain of Debian's mricron-data (ch2better.nii.gz, MNI millimetres), with the AAL "
                              "atlas for --region NAME=label:...");
  image->excludes(colin);
  cmd->add_option("--threshold", opts->anatomy.threshold, "Image: the mask is the voxels above this value")
      ->capture_default_str();
  cmd->add_option("--cut-mm", opts->anatomy.cut_height_mm,
                  "Image: height of the brain's bottom cut away; its flat face is the set 'brainstem_cut' (0: none)")
      ->capture_default_str();
  cmd->add_option("--atlas", opts->anatomy.atlas, "Image: a label image on the same space (its names in <atlas>.txt)");
  cmd->add_option("--region", opts->regions,
                  "Image: a named surface set, NAME=sphere:X,Y,Z,R (mm), NAME=label:LABEL[,LABEL...] (atlas names or "
                  "numbers, e.g. motor=label:Precentral_R) or NAME=below:Z (mm, e.g. base=below:-42); repeat for more");
  cmd->add_option("--opening", opts->opening,
                  "Image: carve a surgical opening (like the ellipsoid's) at X,Y (mm), walls x = X -+ 2 mm, 30 mm along y, "
                  "20 mm deep from the top; or X,Y,WIDTH,LENGTH,DEPTH. Sets opening_left/right/floor")
      ->delimiter(',');
  cmd->add_option("--incision", opts->incision,
                  "Image: refine where an --opening at X,Y (or X,Y,WIDTH,LENGTH,DEPTH) would be, carving nothing: a scenario's "
                  "[[cut]] makes the incision there")
      ->delimiter(',');
  cmd->add_flag("!--no-tissues", opts->anatomy.tissues, "Image: skip the grey_matter / white_matter / csf volume sets");
  cmd->add_option("--seed", opts->anatomy.seed, "Image: CGAL's random seed (the same seed gives the same file)")
      ->capture_default_str();
  cmd->callback([&action, opts, cmd] {
    action = [opts, cmd] {
      if (std::filesystem::is_directory(opts->out))
        throw InputError("--out " + opts->out + ": is a directory; give the mesh file to write (e.g. " +
                         (std::filesystem::path(opts->out) / "brain.msh").string() + ")");
      const bool from_image = opts->colin27 || !opts->image.empty();
      for (const char* image_only :
           {"--threshold", "--cut-mm", "--atlas", "--region", "--opening", "--incision", "--no-tissues", "--seed"})
        if (!from_image && cmd->count(image_only) > 0)
          throw InputError(std::string(image_only) + " applies to image meshes: add --colin27 or --image FILE");
      if (from_image && cmd->count("--slit-refinement") > 0)
        throw InputError("--slit-refinement applies to the ellipsoid brain, not to image meshes");
      if (from_image && cmd->count("--no-opening") > 0)
        throw InputError(
            "--no-opening applies to the ellipsoid brain, not to image meshes (they have no opening unless "
            "--opening asks)");
      if (from_image) {
        anatomy::BrainImageOptions options = opts->anatomy;
        options.target_nodes = opts->nodes;
        options.tolerance = (cmd->count("--tolerance") > 0 ? opts->tolerance : 5.0) / 100.0;
        options.image = opts->image;
        if (opts->colin27) {
          options.image = anatomy::colin27_image();
          if (options.image.empty())
            throw InputError(
                "--colin27: the template is not installed (Debian's mricron-data: sudo apt-get install mricron-data)");
          if (options.atlas.empty()) options.atlas = anatomy::colin27_atlas();
        }
        mesh_image(options, opts->regions, opts->opening, opts->incision, opts->out);
        return;
      }
      Stopwatch clock;
      mesh::BrainShape shape;
      shape.slit_refinement = opts->slit_refinement;
      shape.opening = !opts->no_opening;
      const auto result = mesh::generate_brain_mesh(opts->nodes, opts->out, shape, opts->tolerance / 100.0);
      std::printf("wrote %s: %lld nodes, %lld tetrahedra (element size %.2f mm, %d meshings, %.1f s)\n", opts->out.c_str(),
                  static_cast<long long>(result.mesh.num_nodes()), static_cast<long long>(result.mesh.num_tets()),
                  result.element_size_mm, result.attempts, clock.seconds());
    };
  });
}

void add_info_command(CLI::App& app, Action& action) {
  auto file = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("info", "Print a mesh's size, volume, element quality, bounding box and named sets");
  cmd->add_option("MESH", *file, "Mesh file (any tetrahedral mesh Gmsh reads; lengths in mm)")->required();
  cmd->callback([&action, file] {
    action = [file] {
      const mesh::TetMesh m = mesh::read_mesh(*file);
      mesh::check_mesh(m);
      for (const auto& w : m.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
      const auto s = mesh::mesh_statistics(m);
      const double to_mm = 1.0 / mm;
      std::printf("mesh          %s\n", file->c_str());
      std::printf("nodes         %lld\n", static_cast<long long>(s.nodes));
      std::printf("tetrahedra    %lld\n", static_cast<long long>(s.tets));
      std::printf("volume        %.6g mm^3 (%.4g cm^3)\n", s.volume * 1e9, s.volume * 1e6);
      std::printf("quality       min %.3f, median %.3f  (6 sqrt(2) V / l_rms^3; 1 = regular)\n", s.quality_min, s.quality_median);
      std::printf("bounding box  [%.2f, %.2f] x [%.2f, %.2f] x [%.2f, %.2f] mm\n", s.box_min.x() * to_mm, s.box_max.x() * to_mm,
                  s.box_min.y() * to_mm, s.box_max.y() * to_mm, s.box_min.z() * to_mm, s.box_max.z() * to_mm);
      std::printf("named sets    %zu\n", m.sets.size());
      for (const auto& [name, set] : m.sets)
        std::printf("  %-16s %dD  %6zu nodes  %6zu tetrahedra  %6zu triangles\n", name.c_str(), set.dim, set.nodes.size(),
                    set.tets.size(), set.triangles.size());
    };
  });
}

}  // namespace roifem::app
