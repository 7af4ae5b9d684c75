// A cloth falling onto a sphere resting on a floor, stepped implicitly with a log-barrier contact term (Incremental
// Potential Contact, Li et al. 2020): the solver of <ccdlab/barrier_solver.hpp> (its comment gives the
// energy, the Hessian and the two questions each Newton iteration asks ccdlab), on ccdlab's public API. Each frame
// ends with ccdlab's check that no pair is closer than the separation s; a frame that fails it stops the program
// (exit 1). The `barrier_newton` scene runs the same solver at benchmark size and keeps its CCD queries.
//
//   barrier_cloth [FRAMES] [additive]
// `additive`: the line search's step size from the `additive` tester (Li et al. 2021) at thickness = s, as most
// IPC codes run, instead of ccdlab's certified step; the last line then compares what it changed.
#include <ccdlab/barrier_solver.hpp>
#include <ccdlab/ccdlab.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace bc = ccdlab::barrier;

int main(int argc, char** argv) try {
  const auto started = std::chrono::steady_clock::now();
  bc::ClothScene scene = bc::make_sheet_over_sphere(24, 0.35, 0.25, 12, 24);
  const int sphere_vertices = int(scene.x.size()) - scene.cloth_vertices - 4;
  const std::vector<ccdlab::Detector::Body> bodies{{scene.cloth, scene.cloth_vertices, false, true, "cloth"},
                                                   {scene.sphere, sphere_vertices, true, false, "sphere"},
                                                   {scene.floor, 4, true, false, "floor"}};
  ccdlab::Detector detector(bodies);  // one thread: at 1,500 triangles a query takes well under a millisecond
  bc::Solver<ccdlab::Detector> solver{scene, detector};
  solver.mass = 0.2 / scene.cloth_vertices;  // a 200 g sheet
  std::vector<bc::Point> x = scene.x;
  std::vector<bc::Vec3> v(scene.cloth_vertices, bc::Vec3::Zero());
  const int frames = argc > 1 ? std::atoi(argv[1]) : 60;
  const bool additive = argc > 2 && std::string(argv[2]) == "additive";
  if (argc > 2 && !additive) throw ccdlab::Error(std::string("unknown line search '") + argv[2] + "' (expected: additive)");
  ccdlab::Options additive_options;
  additive_options.tester = "additive:thickness=" + std::to_string(solver.separation);
  ccdlab::Detector additive_detector(bodies, additive_options);
  if (additive) solver.step_detector = &additive_detector;
  int iterations = 0;  // one line search each
  double step_sizes = 0, nearest_ever = solver.dhat;
  for (int frame = 0; frame < frames; ++frame) {
    const auto r = solver.step(x, v);
    iterations += r.iterations, step_sizes += r.step_size_sum;
    // The check: no pair of the frame closer than the separation.
    const ccdlab::Detector::Proximities too_close = detector.proximity(x, solver.separation);
    const ccdlab::Detector::Proximities near = detector.proximity(x, solver.dhat);
    double lowest = 1e9, nearest = solver.dhat;
    for (int i = 0; i < scene.cloth_vertices; ++i) lowest = std::min(lowest, x[i][2]);
    for (const auto* list : {&near.vf, &near.ee})
      for (const auto& p : *list) nearest = std::min(nearest, p.distance);
    nearest_ever = std::min(nearest_ever, nearest);
    if (frame % 10 == 0 || frame + 1 == frames || !too_close.vf.empty() || !too_close.ee.empty())
      std::printf("frame %3d: %2d Newton iterations, %4zu barrier pairs, nearest pair %.6f, lowest cloth point z = %.4f, "
                  "pairs closer than s = %g: %zu\n", frame, r.iterations, r.active, nearest, lowest, solver.separation,
                  too_close.vf.size() + too_close.ee.size());
    if (!too_close.vf.empty() || !too_close.ee.empty()) {
      std::fprintf(stderr, "frame %d ends with pairs closer than the separation\n", frame);
      return 1;
    }
  }
  std::printf("%d frames, every one separated by at least %g; %.1f s\n", frames, solver.separation,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  std::printf("line search: %s; %d Newton iterations, mean collision-free step size %.4f, nearest pair at a frame's "
              "end %.6f\n", additive ? "additive (thickness = s)" : "ccdlab's certified step", iterations,
              iterations ? step_sizes / iterations : 1.0, nearest_ever);
  return 0;
} catch (const ccdlab::Error& e) {
  std::fprintf(stderr, "error: %s\n", e.what());
  return 1;
}
