// The order of the sliver step: the flat flips, then three rounds (volume-neutral moves first,
// moves that fold the surface last) of passes over the slivers, worst first, until a pass
// changes nothing.
#include "union/sliver_collapser.h"

namespace mr::surface_union::slivers {

int Collapser::run(double threshold, const std::vector<char>* seed, const std::vector<double>* cut_distance) {
  threshold_ = threshold;
  // Three rounds: first only moves that give the volume back (a budget of rounding), so
  // the budget is not spent on the worst slivers while cheaper fixes exist; then the rest
  // but those that fold the surface beside the lines (folds_more); then those too, for the
  // slivers nothing else mends.
  const double budget = volume_budget_;
  const double rounding = std::min(budget, 1e-12 * budget_scale_);
  changed_at_.assign(r_.vertices.size(), 0);
  keep_cut_surface();
  if (cut_distance) cut_distance_ = *cut_distance;
  flip_refused_now_.assign(3 * r_.faces.size(), -1);
  removal_refused_now_.assign(r_.vertices.size(), -1);
  slide_refused_now_.assign(r_.vertices.size(), -1);
  relocation_refused_now_.assign(r_.vertices.size(), -1);
  // The flat flips first; the vertices of the faces they changed join the seed.
  std::vector<char> flat_seed;
  changed_.assign(r_.vertices.size(), 0);
  flat_flips_ = flip_flat_slivers(seed);
  if (seed && flat_flips_ > 0) {
    flat_seed = *seed;
    for (size_t x = 0; x < flat_seed.size(); ++x) flat_seed[x] = flat_seed[x] || changed_[x];
    seed = &flat_seed;
  }
  fold_refused_at_.clear();
  for (int round = 0; round < 3; ++round) {
    if (round == 2 && fold_refused_at_.empty()) break;
    ++clock_;
    removal_refused_at_.assign(r_.vertices.size(), -1);
    slide_refused_at_.assign(r_.vertices.size(), -1);
    collapse_refused_at_.clear();
    if (round == 0) volume_budget_ = rounding;
    else if (round == 1) volume_budget_ = budget - (rounding - volume_budget_);
    allow_folds_ = round == 2;
    run_passes(threshold, allow_folds_ ? &fold_refused_at_ : seed);
  }
  allow_folds_ = false;
  return collapses_;
}

double Collapser::hand_over(std::vector<char>& alive, std::vector<char>& cut, std::vector<double>& cut_distance,
                            std::vector<char>& deferred) {
  for (int f = 0; f < int(r_.faces.size()); ++f)
    for (int z = 0; z < 3; ++z) r_.line_edge[f][z] = alive_[f] && line_.count(ekey(r_.faces[f][z], r_.faces[f][(z + 1) % 3])) > 0;
  alive = alive_;
  cut = cut_;
  cut_distance = cut_distance_;
  deferred = deferred_.empty() ? std::vector<char>(r_.vertices.size(), 0) : deferred_;
  return volume_budget_;
}

void Collapser::run_passes(double threshold, const std::vector<char>* seed) {
  if (seed) changed_ = *seed;
  else changed_.assign(r_.vertices.size(), 1);
  for (int pass = 0; pass < 10; ++pass) {
    // After the first pass only slivers whose neighbourhood changed can have new options.
    std::vector<char> changed;
    changed.swap(changed_);
    changed_.assign(r_.vertices.size(), 0);
    std::vector<std::pair<double, int>> bad;
    for (int f = 0; f < int(r_.faces.size()); ++f)
      if (alive_[f] && cut_[f]) {
        const auto& t = r_.faces[f];
        if ((pass > 0 || seed) && !changed[t[0]] && !changed[t[1]] && !changed[t[2]]) continue;
        const double a = min_angle(f);
        if (a < threshold) bad.push_back({a, f});
      }
    std::sort(bad.begin(), bad.end());
    int done = 0;
    for (const auto& [a0, f] : bad) {
      if (!alive_[f] || min_angle(f) >= threshold) continue;
      const auto t = r_.faces[f];
      if ((pass > 0 || seed) && !changed[t[0]] && !changed[t[1]] && !changed[t[2]]) continue;
      // Edges by length, shortest first; each tried in both directions. A cap (one
      // large angle) is first flipped across its longest edge, which moves nothing.
      std::array<std::pair<double, int>, 3> edges;
      for (int z = 0; z < 3; ++z) edges[z] = {norm(sub3(P(t[z]), P(t[(z + 1) % 3]))), z};
      std::sort(edges.begin(), edges.end());
      const bool cap = corner_angle(P(t[(edges[2].second + 2) % 3]), P(t[edges[2].second]), P(t[(edges[2].second + 1) % 3])) >
                       2 * kPi / 3;
      if (cap && try_flip(f, edges[2].second)) { ++done; ++flips_; continue; }
      // Of the allowed collapses, the one that changes the volume least.
      bool ok = false;
      int best_v = -1, best_w = -1;
      double best_dv = 1e300;
      // (A collapse that changes and sweeps no volume, flat stars on CAD plates, cannot be
      // beaten: the rest are not evaluated.)
      for (int e = 0; e < 3 && best_dv > 0; ++e)
        for (int dir = 0; dir < 2 && best_dv > 0; ++dir) {
          const int z = edges[e].second;
          const int a = t[(z + dir) % 3], b = t[(z + 1 - dir) % 3];
          double dv = 0;
          if (try_collapse(a, b, false, &dv, best_dv) && dv < best_dv) { best_dv = dv; best_v = a; best_w = b; }
        }
      if (best_v >= 0 && try_collapse(best_v, best_w)) { ++done; ++collapses_; ok = true; }
      // Or an end of the short edge (then the third corner) leaves, its star filled again.
      for (int c : {t[edges[0].second], t[(edges[0].second + 1) % 3], t[(edges[0].second + 2) % 3]})
        if (!ok && try_remove_vertex(c)) { ++done; ++collapses_; ok = true; }
      // Otherwise a flip of any side may reshape the neighbourhood for a later pass.
      for (int k = 2; k >= 0 && !ok; --k)
        if (try_flip(f, edges[k].second)) { ++done; ++flips_; ok = true; }
      for (int z = 0; z < 3 && !ok; ++z)
        if (try_junction_slide(t[z])) { ++done; ++collapses_; ok = true; }
      // Or a corner slides towards the middle of its ring, within the surface.
      for (int z = 0; z < 3 && !ok; ++z)
        if (try_relocate(t[z])) { ++done; ok = true; }
      for (int z = 0; z < 3 && !ok; ++z)
        if (try_slide_on_line(t[z])) { ++done; ok = true; }
    }
    if (done == 0) break;
  }
}

void Collapser::compact() {
  std::vector<int> index(r_.vertices.size(), -1);
  std::vector<V3> vertices;
  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < int(r_.faces.size()); ++f) {
    if (!alive_[f]) continue;
    std::array<int, 3> t;
    for (int z = 0; z < 3; ++z) {
      const int v = r_.faces[f][z];
      if (index[v] < 0) { index[v] = int(vertices.size()); vertices.push_back(r_.vertices[v]); }
      t[z] = index[v];
    }
    faces.push_back(t);
  }
  std::vector<std::array<bool, 3>> line(faces.size());
  size_t k = 0;
  const bool sources = !r_.face_source.empty();
  for (int f = 0; f < int(r_.faces.size()); ++f) {
    if (!alive_[f]) continue;
    for (int z = 0; z < 3; ++z) line[k][z] = line_.count(ekey(r_.faces[f][z], r_.faces[f][(z + 1) % 3])) > 0;
    if (sources) r_.face_source[k] = r_.face_source[size_t(f)];
    ++k;
  }
  if (sources) r_.face_source.resize(k);
  r_.vertices = std::move(vertices);
  r_.faces = std::move(faces);
  r_.line_edge = std::move(line);
}

}  // namespace mr::surface_union::slivers
