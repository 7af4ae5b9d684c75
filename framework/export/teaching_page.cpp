#include "framework/export/teaching_page.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "ccdlab/teaching_assets.hpp"  // generated from framework/export/teaching/ (CMakeLists.txt)
#include "framework/util/error.hpp"
#include "framework/util/files.hpp"

namespace ccdlab {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    fail("ccdlab export --html: cannot read {} (three.js: install Debian's libjs-three, as "
         "experiments/scripts/install-deps.sh does, or set CCDLAB_THREE_JS to three.min.js)", path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Replaces the one occurrence of `marker` in `page` by `text`.
void put(std::string& page, const std::string& marker, const std::string& text) {
  const std::size_t at = page.find(marker);
  if (at == std::string::npos) fail("teaching page template: marker {} missing", marker);
  page.replace(at, marker.size(), text);
}

/// Text inlined into a <script> element may not close it.
std::string script_safe(std::string text) {
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) text.replace(at, 2, "<\\/");
  return text;
}

}  // namespace

std::string three_js_path() {
  if (const char* env = std::getenv("CCDLAB_THREE_JS"); env && *env) return env;
  return CCDLAB_THREE_JS_DEFAULT;
}

std::string orbit_controls_path() {
  const std::string three = three_js_path();
  return three.substr(0, three.find_last_of('/') + 1) + "examples/js/controls/OrbitControls.js";
}

void write_teaching_page(const std::string& path, const nlohmann::json& data, const std::string& what) {
  std::string page(teaching_assets::page_html);
  put(page, "/*@THREE@*/", script_safe(read_text(three_js_path())));
  put(page, "/*@CONTROLS@*/", script_safe(read_text(orbit_controls_path())));
  put(page, "/*@DATA@*/", script_safe(data.dump()));
  put(page, "/*@PAGE@*/", script_safe(std::string(teaching_assets::page_js)));
  OutputFile out(path, what);
  out << page;
  out.commit();
}

}  // namespace ccdlab
