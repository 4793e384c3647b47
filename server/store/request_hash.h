// The hash that names what a SubmitJob asked for, stored beside a request_id so that a reuse
// of the id with another request is told apart from a retry (JobStore::CreateJob).
#pragma once

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>

#include <string>

#include "radflux/v1/job.pb.h"
#include "wire/scene_hash.h"

namespace radflux {

// Lowercase hex SHA-256 of the scene address and the options' deterministic serialization:
// equal for the same scene and options (the same message), different otherwise.
inline std::string SubmitRequestHash(const std::string& scene_sha256,
                                     const v1::SolveOptions& options) {
  std::string bytes = scene_sha256 + "\n";
  {
    google::protobuf::io::StringOutputStream stream(&bytes);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    options.SerializeToCodedStream(&coded);
  }
  return Sha256Hex(bytes);
}

}  // namespace radflux
