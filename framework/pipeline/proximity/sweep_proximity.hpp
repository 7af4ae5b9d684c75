#pragma once
// The proximity query's reference, beside the query it checks (proximity_query.hpp).
#include "framework/pipeline/bodies.hpp"
#include "framework/primitive/contact.hpp"

namespace ccdlab {

/// The proximity query's reference (and the baseline its benchmark measures): every non-adjacent VF and EE pair of
/// interacting bodies whose exact distance at x is below dhat, found without a hierarchy, ownership or culling
/// stage — a sweep along x of the features' axis-aligned boxes grown by dhat, each pair whose boxes meet decided by
/// the exact static test (framework/primitive/static_distance.hpp). One thread; sorted like the pipeline's contacts
/// (toi 0, coords unset), so contact_set_hash compares the two.
Contacts sweep_proximity(const TriMesh& mesh, const CollisionRules& rules, const Positions& x, double dhat);

}  // namespace ccdlab
