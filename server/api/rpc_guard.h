// The RPC boundary's last line: no exception thrown while serving one call may reach gRPC's
// threads (where it would abort radfluxd). A bug then fails that call with INTERNAL.
#pragma once

#include <spdlog/spdlog.h>

#include <exception>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"

namespace radflux {

// Runs `work` (returning absl::Status or absl::StatusOr<T>) and returns its result; an
// exception it throws is logged with `call` (the RPC's name) and becomes INTERNAL.
template <typename Work>
auto GuardCall(const char* call, Work&& work) noexcept -> decltype(work()) {
  try {
    return work();
  } catch (const std::exception& e) {
    spdlog::error("{} failed with an exception: {}", call, e.what());
    return absl::InternalError(absl::StrCat(call, " failed: internal error (", e.what(), ")"));
  } catch (...) {
    spdlog::error("{} failed with an unknown exception", call);
    return absl::InternalError(absl::StrCat(call, " failed: internal error"));
  }
}

}  // namespace radflux
