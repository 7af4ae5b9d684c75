#pragma once
// The teaching page (`ccdlab export CONFIG --html OUT.html`): one self-contained HTML file — three.js and its
// orbit controls from the Debian package libjs-three, the page's own script (framework/export/teaching/page.js)
// and the scene's data (experiments/cli/export/teaching_data.hpp), all inlined — that opens from disk without a
// server or a network. Its Content-Security-Policy forbids every fetch, so a page that tried would fail visibly.
#include <string>

#include <nlohmann/json.hpp>

namespace ccdlab {

/// Where three.js is read from at export time (found by CMake; CCDLAB_THREE_JS overrides), and its orbit controls.
std::string three_js_path();
std::string orbit_controls_path();

/// Writes the page to `path` (complete or not at all); Error naming `what` (the option) or the missing three.js.
void write_teaching_page(const std::string& path, const nlohmann::json& data, const std::string& what);

}  // namespace ccdlab
