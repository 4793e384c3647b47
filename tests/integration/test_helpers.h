// Helpers shared by the integration tests (service_test.cc, worker_test.cc): the Cornell
// box they submit, and the in-process RunJob their served results are compared against.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "radflux/v1/job.pb.h"
#include "solver/pipeline.h"
#include "solver/scene/obj_loader.h"
#include "tests/source_path.h"
#include "wire/proto_convert.h"

namespace radflux::testing {

// The whole file (empty when it cannot be read).
inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline const std::string kObj = ReadText(SourcePath("scenes/cornell_box.obj"));
inline const std::string kMtl = ReadText(SourcePath("scenes/cornell_box.mtl"));

// B per patch per band of the job `proto` on `scene` computed in-process by RunJob.
inline std::vector<double> InProcess(const v1::SolveOptions& proto, Scene scene) {
  absl::StatusOr<JobOptions> options = FromProto(proto);
  EXPECT_TRUE(options.ok());
  options->form_factors.threads = 2;
  absl::StatusOr<JobResult> result = RunJob(std::move(scene), *options);
  EXPECT_TRUE(result.ok()) << result.status();
  std::vector<double> values;
  for (const Rgb& b : result->solve.radiosity) values.insert(values.end(), b.begin(), b.end());
  return values;
}

// B per patch per band of the same job on the Cornell box computed in-process by RunJob.
inline std::vector<double> InProcess(const v1::SolveOptions& proto) {
  absl::StatusOr<Scene> scene = LoadObjText(kObj, kMtl, "cornell_box.obj");
  EXPECT_TRUE(scene.ok());
  return InProcess(proto, *std::move(scene));
}

// `a` and `b` are the same non-empty values, bit for bit.
inline void ExpectBitIdentical(const std::vector<double>& a, const std::vector<double>& b,
                               const std::string& what = "") {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double))) << what;
}

}  // namespace radflux::testing
