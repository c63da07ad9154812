// Which code renders the reference: "<project version>+<16 hex digits of a SHA-256 over the
// sources of core/ and raymarch/>", generated at build time (app/build_identity.cmake). Part
// of every reference cache key: a changed raymarcher never reuses a stale render.
#pragma once

namespace twinrender::app {

const char* referenceBuildIdentity();
// The same of the real-time renderer (core/ and realtime/ with its shaders): part of the key
// under which a per-set self-check's verdict is remembered (app/per_set_check.h).
const char* realtimeBuildIdentity();

}  // namespace twinrender::app
