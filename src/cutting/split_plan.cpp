// SPDX-License-Identifier: GPL-3.0-or-later
#include "cutting/split_plan.hpp"

#include <algorithm>
#include <limits>
#include <map>

#include "common/errors.hpp"
#include "common/number_text.hpp"

namespace roifem::cutting {

SplitPlan plan_splits(const std::vector<Blade>& blades, const mesh::TetMesh& mesh, double t_end) {
  SplitPlan plan;
  plan.num_nodes = mesh.num_nodes();
  plan.neighbours = face_neighbours(mesh);
  std::map<std::pair<Index, Index>, std::pair<double, const Blade*>> first;
  for (const Blade& blade : blades) {
    if (blade.mode != CutMode::split) continue;
    const std::vector<SeparatedFace> faces = separated_faces(blade, mesh, plan.neighbours);
    if (faces.empty())
      throw InputError(blade.where + ": " + blade.describe() + " never meets the mesh " + mesh.source +
                       ": its edge, swept along its path, separates no face");
    if (faces.front().time > t_end * (1 + 1e-12))
      throw InputError(blade.where + ": " + blade.describe() + " first separates a face (between tetrahedra " +
                       std::to_string(faces.front().a) + " and " + std::to_string(faces.front().b) + ") at t = " +
                       number_text(faces.front().time) + " s, after the run ends at t = " + number_text(t_end) + " s");
    for (const SeparatedFace& f : faces) {
      if (f.time > t_end * (1 + 1e-12)) continue;
      const auto [it, fresh] = first.try_emplace({f.a, f.b}, f.time, &blade);
      if (!fresh && f.time < it->second.first) it->second = {f.time, &blade};
    }
  }
  for (const auto& [face, when] : first) {
    plan.faces.push_back({face.first, face.second, when.first});
    plan.blade_of.push_back(when.second);
  }
  std::vector<std::size_t> order(plan.faces.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return plan.faces[x].time < plan.faces[y].time; });
  std::vector<SeparatedFace> faces;
  std::vector<const Blade*> blade_of;
  for (const std::size_t i : order) {
    faces.push_back(plan.faces[i]);
    blade_of.push_back(plan.blade_of[i]);
  }
  plan.faces = std::move(faces);
  plan.blade_of = std::move(blade_of);

  // The dry run: which nodes split, and how often.
  NodeSplitter dry(mesh.tets, plan.neighbours, mesh.num_nodes());
  std::vector<std::pair<Index, Index>> all;
  for (const SeparatedFace& f : plan.faces) all.emplace_back(f.a, f.b);
  dry.separate(all);
  plan.copies.assign(static_cast<std::size_t>(mesh.num_nodes()), {});
  std::vector<int> count(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const auto& [copy, original] : dry.copies_made()) ++count[static_cast<std::size_t>(original)];
  for (int n = 0; n < mesh.num_nodes(); ++n)
    for (int k = 0; k < count[static_cast<std::size_t>(n)]; ++k) {
      plan.copies[static_cast<std::size_t>(n)].push_back(static_cast<int>(mesh.num_nodes() + plan.num_copies()));
      plan.copy_of.push_back(n);
    }
  return plan;
}

std::vector<std::pair<Rewire, std::size_t>> rehearse(const SplitPlan& plan, const std::vector<mesh::Tet>& tets,
                                                     const std::vector<bool>& anchored) {
  NodeSplitter rehearsal(tets, plan.neighbours, plan.num_nodes, {}, anchored);
  std::vector<std::pair<Rewire, std::size_t>> moves;
  for (std::size_t i = 0; i < plan.faces.size(); ++i)
    for (const Rewire& move : rehearsal.separate({{plan.faces[i].a, plan.faces[i].b}})) moves.emplace_back(move, i);
  return moves;
}

mesh::TetMesh with_copies(mesh::TetMesh mesh, const SplitPlan& plan) {
  const Index n = mesh.num_nodes();
  if (n != plan.num_nodes) throw Error("internal: a split plan for another mesh");
  mesh.nodes.conservativeResize(3, n + plan.num_copies());
  for (Index k = 0; k < plan.num_copies(); ++k) mesh.nodes.col(n + k) = mesh.nodes.col(plan.copy_of[static_cast<std::size_t>(k)]);
  return mesh;
}

}  // namespace roifem::cutting
