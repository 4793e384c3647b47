// The page of `radflux view`, embedded in radflux-service at build time from
// client/view/index.html and client/view/view.js (embed_assets.cmake), so the binary
// needs no page files beside it; three.js is served from its installed files instead.
#pragma once

namespace radflux::cli {

extern const char kViewIndexHtml[];  // the page, for every view (job, job list, saved result)
extern const char kViewJs[];         // its script
}  // namespace radflux::cli
