// Principal: who a call comes from (a named client of radfluxd, see server/api/principals.h),
// what it may see, and the limits on what it may submit. Jobs and scenes belong to the
// principal that made them; a principal sees only its own, an admin sees all.
#pragma once

#include <cstdint>
#include <string>

namespace radflux {

// The principal of the single --token, of a server without tokens (everyone), of workers
// fetching scenes, and the owner of jobs and scenes stored before principals existed.
inline constexpr char kDefaultPrincipal[] = "default";

// Per-principal limits on submits; 0 = no limit of the principal's own (the server's
// limits, e.g. --max-patches, still apply).
struct PrincipalLimits {
  int64_t running_jobs = 0;  // the principal's jobs QUEUED or RUNNING at once
  int64_t patches = 0;       // patches of one job (min with --max-patches)
  double cpu_seconds = 0;    // CPU time of one job: its threads x its running time, seconds
};

struct Principal {
  std::string name;
  bool admin = false;  // sees, cancels and fetches every principal's jobs and scenes
  PrincipalLimits limits;

  // Whether this principal may see what `owner` made: its own, or anything for an admin.
  bool Sees(const std::string& owner) const { return admin || owner == name; }
};

}  // namespace radflux
