#pragma once
// PrimitiveTester: the elementary continuous tests (vertex–face, edge–edge) under linear motion over one
// step. Implementations form the accuracy ladder (float, filtered, conservative, exact); strategies/testers/.
#include <string_view>

#include "framework/primitive/contact.hpp"

namespace ccdlab {

class PrimitiveTester {
 public:
  virtual ~PrimitiveTester() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Contact distance η ≥ 0: features closer than η count as touching. The broad phase inflates by it too.
  [[nodiscard]] virtual double thickness() const = 0;
  [[nodiscard]] virtual CcdHit vertex_face(const VertexFaceQuery& q) const = 0;
  [[nodiscard]] virtual CcdHit edge_edge(const EdgeEdgeQuery& q) const = 0;
};

}  // namespace ccdlab
