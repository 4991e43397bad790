// The scripts and style every page embeds, compiled in from their files at build time
// (embed_assets.cmake): three.js r111 and its OrbitControls from Debian's libjs-three, and the
// viewer's own page.js and page.css.
#pragma once

namespace roving::html_assets {

extern const char* const three_js;
extern const char* const orbit_controls_js;
extern const char* const page_js;
extern const char* const page_css;

}  // namespace roving::html_assets
