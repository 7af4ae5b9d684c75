#include "strategies/registry.hpp"

#include "strategies/builders/median_builder.hpp"
#include "strategies/builders/sah_builder.hpp"
#include "strategies/effects/effects.hpp"
#include "strategies/scenes/drape_fold_scene.hpp"
#include "strategies/scenes/barrier_newton_scene.hpp"
#include "strategies/scenes/simulated_scene.hpp"
#include "strategies/schedulers/front_scheduler.hpp"
#include "strategies/schedulers/phc_scheduler.hpp"
#include "strategies/schedulers/embree_scheduler.hpp"
#include "strategies/schedulers/sequential_scheduler.hpp"
#include "strategies/schedulers/static_scheduler.hpp"
#include "strategies/testers/additive_tester.hpp"
#include "strategies/testers/conservative_tester.hpp"
#include "strategies/testers/exact_tester.hpp"
#include "strategies/testers/filtered_tester.hpp"
#include "strategies/testers/float_tester.hpp"
#include "strategies/testers/inclusion_tester.hpp"

namespace ccdlab {

const BuilderRegistry& builder_registry() {
  static const BuilderRegistry r = [] {
    BuilderRegistry r("hierarchy");
    r.add({"median", "top-down, median split of centroids on the widest axis (balanced)", {},
           [](const ParamValues&) -> std::unique_ptr<HierarchyBuilder> { return std::make_unique<MedianBuilder>(); }});
    r.add({"sah", "top-down binned surface-area heuristic (Wald 2007)",
           {{"bins", ParamType::integer, (long long)SahBuilder::Params{}.bins, "bins per axis", 2, 256}},
           [](const ParamValues& p) -> std::unique_ptr<HierarchyBuilder> {
             return std::make_unique<SahBuilder>(SahBuilder::Params{int(p.integer("bins"))});
           }});
    return r;
  }();
  return r;
}

const SchedulerRegistry& scheduler_registry() {
  static const SchedulerRegistry r = [] {
    SchedulerRegistry r("scheduler");
    r.add({"sequential", "depth-first BVTT traversal from the root on one thread (ICCD baseline)", {},
           [](const ParamValues&) -> std::unique_ptr<TraversalScheduler> {
             return std::make_unique<SequentialScheduler>();
           }});
    r.add({"phc", "breadth-first top until c*threads sub-tasks, then sub-tasks in parallel, dynamic (MCCD)",
           {{"c", ParamType::integer, (long long)PhcScheduler::Params{}.tasks_per_thread, "sub-tasks per thread", 1, 100000}},
           [](const ParamValues& p) -> std::unique_ptr<TraversalScheduler> {
             return std::make_unique<PhcScheduler>(PhcScheduler::Params{int(p.integer("c"))});
           }});
    r.add({"front", "BVTT front kept across steps, processed in parallel chunks; sprout, prune, rebuild (the paper)",
           {{"chunk", ParamType::integer, (long long)FrontScheduler::Params{}.chunk, "front entries per task: node pairs (bv.width 2) or record pairs (4)", 1, 1 << 24},
            {"prune", ParamType::boolean, FrontScheduler::Params{}.prune, "collapse non-overlapping siblings into their parent", 0, 0},
            {"rebuild_growth", ParamType::real, FrontScheduler::Params{}.rebuild_growth, "rebuild when the front grows past this x its rebuilt size (0 = never)", 0, 1e9},
            {"rebuild_every", ParamType::integer, (long long)FrontScheduler::Params{}.rebuild_every, "also rebuild every N steps (0 = never)", 0, 1 << 30}},
           [](const ParamValues& p) -> std::unique_ptr<TraversalScheduler> {
             return std::make_unique<FrontScheduler>(FrontScheduler::Params{
                 int(p.integer("chunk")), p.boolean("prune"), p.real("rebuild_growth"), int(p.integer("rebuild_every"))});
           }});
    r.add({"static", "c*threads sub-tasks fixed per thread before each step: equal-count chunks, then by the last step's costs (Grinberg)",
           {{"c", ParamType::integer, (long long)StaticScheduler::Params{}.tasks_per_thread, "sub-tasks per thread", 1, 100000}},
           [](const ParamValues& p) -> std::unique_ptr<TraversalScheduler> {
             return std::make_unique<StaticScheduler>(StaticScheduler::Params{int(p.integer("c"))});
           }});
    r.add({"embree", "Intel Embree's rtcCollide over the leaves' boxes, then the leaf k-DOPs: the industry's broad phase, "
           "side by side", {},
           [](const ParamValues&) -> std::unique_ptr<TraversalScheduler> { return std::make_unique<EmbreeScheduler>(); }});
    return r;
  }();
  return r;
}

const TesterRegistry& tester_registry() {
  static const TesterRegistry r = [] {
    TesterRegistry r("tester");
    r.add({"float", "cubic coplanarity roots in double, then a proximity check (not conservative)",
           {{"thickness", ParamType::real, FloatTester::Params{}.thickness, "contact distance eta (scene units)", 0, 1e300}},
           [](const ParamValues& p) -> std::unique_ptr<PrimitiveTester> {
             return std::make_unique<FloatTester>(FloatTester::Params{p.real("thickness")});
           }});
    r.add({"filtered", "certified Bernstein non-penetration filter (Tang 2010), then float; zero thickness", {},
           [](const ParamValues&) -> std::unique_ptr<PrimitiveTester> { return std::make_unique<FilteredTester>(); }});
    r.add({"additive", "additive CCD (Li et al. 2021): distance steps that cannot close the gap, until it falls "
           "below (1 - eta) of its start; fast, not conservative; reports pairs that approach, the time early",
           {{"eta", ParamType::real, AdditiveTester::Params{}.eta, "fraction of the gap one step may close (C-IPC's 1 - s)", 1e-6, 1 - 1e-6},
            {"thickness", ParamType::real, AdditiveTester::Params{}.thickness, "minimum separation xi (scene units)", 0, 1e300},
            {"max_iterations", ParamType::integer, (long long)AdditiveTester::Params{}.max_iterations, "steps per query before the fallback (a hit)", 1, 1 << 30}},
           [](const ParamValues& p) -> std::unique_ptr<PrimitiveTester> {
             return std::make_unique<AdditiveTester>(
                 AdditiveTester::Params{p.real("eta"), p.real("thickness"), int(p.integer("max_iterations"))});
           }});
    r.add({"conservative", "certified bisection: never misses; in time with Bernstein bounds, or with thickness eta > 0 "
           "in time and on the features (minimum separation)",
           {{"delta", ParamType::real, ConservativeTester::Params{}.delta, "relative tolerance: undecided once features move < delta*size in a window", 0, 1},
            {"fallback", ParamType::string, std::string("hit"), "what an undecided query becomes: hit or exact", 0, 0, {"hit", "exact"}},
            {"max_windows", ParamType::integer, (long long)ConservativeTester::Params{}.max_windows, "time windows per query before the fallback", 1, 1 << 20},
            {"toi_tolerance", ParamType::real, ConservativeTester::Params{}.toi_tolerance, "width of the time window reported for a hit", 0, 1},
            {"thickness", ParamType::real, ConservativeTester::Params{}.thickness, "contact distance eta (scene units): every pair that comes within it", 0, 1e300},
            {"max_boxes", ParamType::integer, (long long)ConservativeTester::Params{}.max_boxes, "with thickness: boxes of (t, u, v) per query before the fallback", 1, 1 << 24}},
           [](const ParamValues& p) -> std::unique_ptr<PrimitiveTester> {
             return std::make_unique<ConservativeTester>(ConservativeTester::Params{
                 p.real("delta"), ConservativeTester::parse_fallback(p.string("fallback")), int(p.integer("max_windows")),
                 p.real("toi_tolerance"), p.real("thickness"), int(p.integer("max_boxes"))});
           }});
    r.add({"inclusion", "inclusion-based CCD (Wang et al. 2021): earliest-first (t, u, v) boxes, corner-value "
           "inclusions with a rounding filter; never misses",
           {{"delta", ParamType::real, InclusionTester::Params{}.delta, "relative tolerance: accept a box whose image is < delta*size", 0, 1},
            {"max_boxes", ParamType::integer, (long long)InclusionTester::Params{}.max_boxes, "boxes per query before the fallback (a hit)", 1, 1 << 30},
            {"min_separation", ParamType::real, InclusionTester::Params{}.min_separation, "ms: contact when every coordinate of the gap is within ms (scene units)", 0, 1e300}},
           [](const ParamValues& p) -> std::unique_ptr<PrimitiveTester> {
             return std::make_unique<InclusionTester>(
                 InclusionTester::Params{p.real("delta"), int(p.integer("max_boxes")), p.real("min_separation")});
           }});
    r.add({"exact", "reference: exact algebraic roots and signs on GMP integers (CGAL); zero thickness",
           {{"prefilter", ParamType::boolean, ExactTester::Params{}.prefilter, "decide certainly separated queries by interval bounds first", 0, 0},
            {"certify", ParamType::boolean, ExactTester::Params{}.certify, "decide most queries (true contacts too) by interval classification "
             "of the coplanarity windows before any algebra", 0, 0}},
           [](const ParamValues& p) -> std::unique_ptr<PrimitiveTester> {
             return std::make_unique<ExactTester>(ExactTester::Params{p.boolean("prefilter"), p.boolean("certify")});
           }});
    return r;
  }();
  return r;
}

const EffectRegistry& effect_registry() {
  static const EffectRegistry r = [] {
    EffectRegistry r("effect");
    using P = ParamType;
    const GravityParams gravity;
    r.add({"gravity", "constant acceleration of every free vertex",
           {{"gx", P::real, gravity.g.x(), "m/s^2", -1e3, 1e3}, {"gy", P::real, gravity.g.y(), "m/s^2", -1e3, 1e3},
            {"gz", P::real, gravity.g.z(), "m/s^2", -1e3, 1e3}},
           make_gravity});
    r.add({"damping", "velocities decay as exp(-rate t)", {{"rate", P::real, DampingParams{}.rate, "1/s", 0, 1e6}}, make_damping});
    const WindParams wind;
    r.add({"wind", "drag towards a wind velocity on each triangle's normal, with seeded gusts",
           {{"vx", P::real, wind.velocity.x(), "m/s", -1e3, 1e3}, {"vy", P::real, wind.velocity.y(), "m/s", -1e3, 1e3},
            {"vz", P::real, wind.velocity.z(), "m/s", -1e3, 1e3},
            {"drag", P::real, wind.drag, "drag coefficient (per unit area and mass)", 0, 1e6},
            {"turbulence", P::real, wind.turbulence, "gust amplitude relative to the wind speed", 0, 10}},
           make_wind});
    r.add({"stretch", "XPBD distance constraints on every cloth edge (stretch and shear)",
           {{"compliance", P::real, StretchParams{}.compliance, "inverse stiffness, m/N (0 = inextensible)", 0, 1}}, make_stretch});
    r.add({"bend", "XPBD distance constraints across every interior edge",
           {{"compliance", P::real, BendParams{}.compliance, "inverse stiffness, m/N", 0, 1}}, make_bend});
    const PinParams pin;
    r.add({"pin", "fixes (or moves as a scripted handle) the cloth vertices whose rest position is in a box",
           {{"min_x", P::real, pin.lo.x(), "box, rest coordinates", -1e9, 1e9}, {"min_y", P::real, pin.lo.y(), "", -1e9, 1e9},
            {"min_z", P::real, pin.lo.z(), "", -1e9, 1e9}, {"max_x", P::real, pin.hi.x(), "", -1e9, 1e9},
            {"max_y", P::real, pin.hi.y(), "", -1e9, 1e9}, {"max_z", P::real, pin.hi.z(), "", -1e9, 1e9},
            {"vx", P::real, pin.velocity.x(), "handle velocity, m/s", -1e3, 1e3}, {"vy", P::real, pin.velocity.y(), "", -1e3, 1e3},
            {"vz", P::real, pin.velocity.z(), "", -1e3, 1e3}, {"move_start", P::real, pin.move_start, "s", 0, 1e9},
            {"move_end", P::real, pin.move_end, "s", 0, 1e9},
            {"follow", P::string, pin.follow, "move rigidly with this obstacle (a waistband on a body)", 0, 0}},
           make_pin});
    r.add({"obstacle_contact", "pushes cloth out of sphere and capsule obstacles (exact shapes), with friction",
           {{"friction", P::real, ObstacleContactParams{}.friction, "Coulomb coefficient", 0, 10}}, make_obstacle_contact});
    const CcdContactParams contact;
    r.add({"ccd_contact", "crossing-free sub-steps: ccdlab's CCD, impulses, then rigid impact zones",
           {{"self", P::boolean, contact.self, "self-contact of the cloth (false: cloth-obstacle only; no self pass runs)", 0, 0},
            {"iterations", P::integer, (long long)contact.iterations, "impulse rounds before the impact zones", 1, 1000},
            {"k", P::integer, (long long)contact.k, fmt::format("k-DOP of the CCD's BVH: {}", kKdopKs), 6, 26},
            {"scheduler", P::string, contact.scheduler, "the CCD's traversal scheduler", 0, 0,
             {"sequential", "phc", "front", "static"}}},
           make_ccd_contact});
    return r;
  }();
  return r;
}

PipelineStrategies contact_strategies(int k, const std::string& scheduler, int threads, double thickness) {
  PipelineStrategies s;
  s.k = k;
  s.threads = threads;
  s.builder = builder_registry().make({kDefaultHierarchy, builder_registry().find(kDefaultHierarchy)->defaults()});
  s.scheduler = scheduler_registry().make({scheduler, scheduler_registry().find(scheduler)->defaults()});
  ParamValues tester = tester_registry().find("float")->defaults();
  tester.set("thickness", thickness);
  s.tester = tester_registry().make({"float", tester});
  return s;
}

Simulator make_simulator(const SimScene& scene, const TriMesh& mesh) {
  SimSetup setup = scene.setup;
  setup.mesh = &mesh;
  std::vector<std::unique_ptr<Effect>> effects;
  for (const StrategyChoice& c : scene.effects) effects.push_back(effect_registry().make(c));
  return Simulator(std::move(setup), std::move(effects), scene.options);
}

const SceneRegistry& scene_registry() {
  static const SceneRegistry r = [] {
    SceneRegistry r("scene.builtin");
    DrapeFoldParams d;
    r.add({"drape_fold", "kinematic cloth sheet folding onto itself while draped over a moving sphere",
           {{"resolution", ParamType::integer, (long long)d.resolution, "grid cells per side (2*res^2 triangles)", 1, 4000},
            {"num_frames", ParamType::integer, (long long)d.frames, "number of frames (steps + 1)", 2, 100000},
            {"fold_deg", ParamType::real, d.fold_deg, "final fold angle, degrees (0 = no fold)", 0, 360},
            {"crease", ParamType::real, d.crease, "crease position in material x", -0.99, 0.99},
            {"crease_radius", ParamType::real, d.crease_radius, "radius of the round crease", 1e-6, 1},
            {"wrinkle", ParamType::real, d.wrinkle, "wrinkle amplitude (0 = flat)", 0, 1},
            {"sphere_radius", ParamType::real, d.sphere_radius, "sphere radius (0 = no sphere)", 0, 10},
            {"sphere_segments", ParamType::integer, (long long)d.sphere_segments, "sphere tessellation", 4, 1024},
            {"sphere_travel", ParamType::real, d.sphere_travel, "sphere moves from -travel to +travel in x", 0, 10},
            {"self_collision", ParamType::boolean, d.self_collision, "test the cloth against itself", 0, 0}},
           [](const ParamValues& p) {
             DrapeFoldParams d;
             d.resolution = int(p.integer("resolution"));
             d.frames = int(p.integer("num_frames"));
             d.fold_deg = p.real("fold_deg");
             d.crease = p.real("crease");
             d.crease_radius = p.real("crease_radius");
             d.wrinkle = p.real("wrinkle");
             d.sphere_radius = p.real("sphere_radius");
             d.sphere_segments = int(p.integer("sphere_segments"));
             d.sphere_travel = p.real("sphere_travel");
             d.self_collision = p.boolean("self_collision");
             return make_drape_fold_scene(d);
           },
           [](const ParamValues& p) {
             const std::uint64_t n = std::uint64_t(p.integer("resolution")), s = std::uint64_t(p.integer("sphere_segments"));
             return 2 * n * n + (p.real("sphere_radius") > 0 ? s * s : 0);  // sheet + sphere (s longitudes × s/2 latitudes × 2)
           }});
    r.add({"simulated", "a scene of the simulator (experiments/scenes/*.yaml), simulated once and cached by its hash",
           {{"file", ParamType::string, std::string(), "the scene file (relative to the working directory)", 0, 0},
            {"num_frames", ParamType::integer, 0LL, "frames to simulate (0 = the scene's own)", 0, 1000000},
            {"first_frame", ParamType::integer, 0LL, "the first frame CCD steps from (earlier frames are simulated, not stepped)", 0, 1000000},
            {"last_frame", ParamType::integer, 0LL, "the last frame CCD steps to (0 = the last simulated)", 0, 1000000},
            {"resolution", ParamType::real, 0.0, "size factor (0 = the scene's own; 1 = full size)", 0, 100},
            {"threads", ParamType::integer, 0LL, "simulation threads (0 = the scene's own; frames do not depend on it)", 0, 1024},
            {"dir", ParamType::string, std::string(), "folder of the frames (empty = results/scenes/NAME-HASH)", 0, 0}},
           [](const ParamValues& p) {
             if (p.string("file").empty()) fail("scene: builtin: simulated needs file: experiments/scenes/NAME.yaml");
             SimulateRequest request{p.string("file"), {}, p.string("dir"), false, true};
             if (p.integer("num_frames") > 0) request.overrides.push_back(fmt::format("frames={}", p.integer("num_frames")));
             if (p.real("resolution") > 0) request.overrides.push_back(fmt::format("resolution={}", p.real("resolution")));
             if (p.integer("threads") > 0) request.overrides.push_back(fmt::format("threads={}", p.integer("threads")));
             return load_simulated_frames(simulate_to_folder(request, false), int(p.integer("first_frame")),
                                          int(p.integer("last_frame")));
           }});
    BarrierNewtonParams b;
    r.add({"barrier_newton", "the CCD queries of a barrier (IPC) solver: a pleated sheet dropped on a sphere, each Newton iteration's x and x + dx",
           {{"cells", ParamType::integer, (long long)b.cells, "vertices per side of the sheet (2*(cells-1)^2 triangles)", 8, 2000},
            {"pleats", ParamType::integer, (long long)b.pleats, "layers of the sheet's accordion fold", 1, 64},
            {"solver_frames", ParamType::integer, (long long)b.frames, "solver frames (1/60 s each)", 1, 10000},
            {"max_iterations", ParamType::integer, (long long)b.max_iterations, "Newton iterations per frame at most", 1, 1000},
            {"slide_speed", ParamType::real, b.slide_speed, "each layer's initial speed along the folds, m/s (alternating)", 0, 100},
            {"wrinkle", ParamType::real, b.wrinkle, "each layer's waves, in layer gaps (0 = flat)", 0, 10},
            {"drop_speed", ParamType::real, b.drop_speed, "the top layer's initial downward speed, m/s (the lowest at rest)", 0, 100},
            {"first_frame", ParamType::integer, 0LL, "the first recorded frame CCD steps from (query i: frames 2i, 2i+1)", 0, 1000000},
            {"last_frame", ParamType::integer, 0LL, "the last recorded frame CCD steps to (0 = the last)", 0, 1000000},
            {"dir", ParamType::string, std::string(), "folder of the recording (empty = results/scenes/barrier_newton-HASH)", 0, 0}},
           [](const ParamValues& p) {
             BarrierNewtonParams b;
             b.cells = int(p.integer("cells"));
             b.pleats = int(p.integer("pleats"));
             b.frames = int(p.integer("solver_frames"));
             b.max_iterations = int(p.integer("max_iterations"));
             b.drop_speed = p.real("drop_speed");
             b.wrinkle = p.real("wrinkle");
             b.slide_speed = p.real("slide_speed");
             b.dir = p.string("dir");
             return load_simulated_frames(record_barrier_newton(b), int(p.integer("first_frame")), int(p.integer("last_frame")));
           },
           [](const ParamValues& p) {
             const std::uint64_t n = std::uint64_t(p.integer("cells")) - 1;
             return 2 * n * n + 2 * 16 * 32 + 2;  // sheet + sphere + floor
           }});
    return r;
  }();
  return r;
}

Registries builtin_registries() {
  return {builder_registry(), scheduler_registry(), tester_registry(), scene_registry()};
}

}  // namespace ccdlab
