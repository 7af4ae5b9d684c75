// stretch: XPBD distance constraints on every cloth edge. On our triangulated grids the edges are the
// structural springs plus one diagonal per quad, so in-plane shear is resisted too (a second diagonal set would
// add isotropy at 50% more constraints; the paper's cloth data are triangle meshes, where edges are what exists).
#include "strategies/effects/effects.hpp"
#include "strategies/effects/xpbd_distance.hpp"

namespace ccdlab {
namespace {

class Stretch final : public Effect {
 public:
  explicit Stretch(double compliance) : compliance_(compliance) {}
  [[nodiscard]] std::string_view name() const override { return "stretch"; }
  [[nodiscard]] Stage stage() const override { return Stage::constraint; }
  [[nodiscard]] std::string_view work_name() const override { return "constraints projected"; }
  void setup(SimSetup& setup) override {
    const TriMesh& mesh = *setup.mesh;
    const std::vector<char> cloth = setup.cloth_mask();
    for (Index e = 0; e < mesh.num_edges(); ++e) {
      const auto& edge = mesh.edge(e);
      if (cloth[std::size_t(edge[0])] && cloth[std::size_t(edge[1])]) c_.add(edge[0], edge[1], setup.rest);
    }
  }
  std::uint64_t apply(const SimSetup& setup, SimState& s, double dt) override { return c_.project(setup, s, dt, compliance_); }

 private:
  double compliance_;
  DistanceConstraints c_;
};

}  // namespace

std::unique_ptr<Effect> make_stretch(const ParamValues& p) { return std::make_unique<Stretch>(p.real("compliance")); }

}  // namespace ccdlab
