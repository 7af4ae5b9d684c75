// step_contacts T0 T1 [OPTIONS_YAML]: every contact while the mesh moves from T0 to T1 (same topology), as CSV
// on stdout — kind,a,b,c,d,toi,u,v,nx,ny,nz, the columns of `ccdlab step --contacts` — and a summary on stderr.
// OPTIONS_YAML is YAML text with the strategy keys of an experiment, e.g. "{scheduler: phc, threads: 2}".
#include <ccdlab/ccdlab.hpp>

#include <algorithm>
#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s T0 T1 [OPTIONS_YAML]\n", argv[0]);
    return 2;
  }
  try {
    const ccdlab::MeshFile t0 = ccdlab::read_mesh(argv[1]);
    const ccdlab::MeshFile t1 = ccdlab::read_mesh(argv[2]);
    if (t0.faces != t1.faces) {
      std::fprintf(stderr, "%s and %s do not have the same faces\n", argv[1], argv[2]);
      return 1;
    }
    const ccdlab::Options options = ccdlab::Options::from_yaml(argc == 4 ? argv[3] : "", "OPTIONS_YAML");
    ccdlab::Detector detector(t0.faces, options);
    const ccdlab::Detector::Contacts contacts = detector.step(t0.positions, t1.positions);

    std::printf("kind,a,b,c,d,toi,u,v,nx,ny,nz\n");
    double earliest = 1.0;
    for (const auto* list : {&contacts.vf, &contacts.ee})
      for (const ccdlab::Detector::Contact& c : *list) {
        std::printf("%s,%d,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", list == &contacts.vf ? "vf" : "ee",
                    c.vertices[0], c.vertices[1], c.vertices[2], c.vertices[3], c.toi, c.coords[0], c.coords[1],
                    c.normal[0], c.normal[1], c.normal[2]);
        earliest = std::min(earliest, c.toi);
      }
    std::fprintf(stderr, "%zu vertices, %zu faces: %zu VF and %zu EE contacts, earliest at t = %.17g\n",
                 t0.positions.size(), t0.faces.size(), contacts.vf.size(), contacts.ee.size(), earliest);
    return 0;
  } catch (const ccdlab::Error& e) {  // bad files or options: the message names the call, file and field
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
