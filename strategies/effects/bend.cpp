// bend: XPBD distance constraints between the two vertices opposite each interior cloth edge (the cross-edge
// spring of Provot 1995 / Müller 2007). Chosen over the dihedral-angle constraint because it is one distance
// per edge — the same cheap, stable projection as stretch — and cloth at our resolutions bends little per edge;
// its weakness (it also resists in-plane compression across the edge) is what cloth wants anyway.
#include "strategies/effects/effects.hpp"
#include "strategies/effects/xpbd_distance.hpp"

namespace ccdlab {
namespace {

class Bend final : public Effect {
 public:
  explicit Bend(double compliance) : compliance_(compliance) {}
  [[nodiscard]] std::string_view name() const override { return "bend"; }
  [[nodiscard]] Stage stage() const override { return Stage::constraint; }
  [[nodiscard]] std::string_view work_name() const override { return "constraints projected"; }
  void setup(SimSetup& setup) override {
    const TriMesh& mesh = *setup.mesh;
    const std::vector<char> cloth = setup.cloth_mask();
    auto opposite = [&](Index f, Index a, Index b) {
      for (Index v : mesh.face(f))
        if (v != a && v != b) return v;
      return Index(-1);
    };
    for (Index e = 0; e < mesh.num_edges(); ++e) {
      const auto faces = mesh.edge_faces(e);
      if (faces.size() != 2) continue;
      const auto& edge = mesh.edge(e);
      const Index u = opposite(faces[0], edge[0], edge[1]), w = opposite(faces[1], edge[0], edge[1]);
      if (u >= 0 && w >= 0 && cloth[std::size_t(u)] && cloth[std::size_t(w)]) c_.add(u, w, setup.rest);
    }
  }
  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override { return c_.project(setup, s, dt, compliance_); }

 private:
  double compliance_;
  DistanceConstraints c_;
};

}  // namespace

std::unique_ptr<Effect> make_bend(const ParamValues& p) { return std::make_unique<Bend>(p.real("compliance")); }

}  // namespace ccdlab
