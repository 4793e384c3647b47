#include "server/result_codec.h"

#include <algorithm>
#include <cstring>

namespace radflux {

std::vector<v1::ResultChunk> MakeResultChunks(const PatchMesh& mesh, const SolveResult& solve,
                                              const std::string& report_json) {
  std::vector<v1::ResultChunk> chunks(1);
  v1::ResultHeader* header = chunks[0].mutable_header();
  header->set_vertex_count(mesh.positions.size());
  header->set_patch_count(mesh.size());
  for (size_t first = 0; first < mesh.positions.size(); first += kResultChunkItems) {
    v1::VertexChunk* v = chunks.emplace_back().mutable_vertices();
    v->set_first_vertex(first);
    const size_t end = std::min(mesh.positions.size(), first + kResultChunkItems);
    for (size_t i = first; i < end; ++i) {
      v->add_xyz(mesh.positions[i].x);
      v->add_xyz(mesh.positions[i].y);
      v->add_xyz(mesh.positions[i].z);
    }
  }
  for (size_t first = 0; first < mesh.size(); first += kResultChunkItems) {
    v1::PatchChunk* p = chunks.emplace_back().mutable_patches();
    p->set_first_patch(first);
    const size_t end = std::min(mesh.size(), first + kResultChunkItems);
    for (size_t i = first; i < end; ++i) {
      for (uint32_t v : mesh.patches[i].v) p->add_vertices(v);
      p->add_source_face(mesh.patches[i].face);
      for (double b : solve.radiosity[i]) p->add_radiosity(b);
    }
  }
  chunks.emplace_back().set_report_json(report_json);
  return chunks;
}

std::string EncodeResultChunks(const std::vector<v1::ResultChunk>& chunks) {
  std::string out;
  for (const v1::ResultChunk& chunk : chunks) {
    const std::string bytes = chunk.SerializeAsString();
    const uint64_t size = bytes.size();
    out.append(reinterpret_cast<const char*>(&size), sizeof(size));
    out += bytes;
  }
  return out;
}

absl::StatusOr<std::vector<v1::ResultChunk>> DecodeResultChunks(const std::string& bytes) {
  std::vector<v1::ResultChunk> chunks;
  size_t at = 0;
  while (at < bytes.size()) {
    uint64_t size = 0;
    if (bytes.size() - at < sizeof(size)) return absl::DataLossError("truncated result");
    std::memcpy(&size, bytes.data() + at, sizeof(size));
    at += sizeof(size);
    if (bytes.size() - at < size) return absl::DataLossError("truncated result");
    if (!chunks.emplace_back().ParseFromArray(bytes.data() + at, static_cast<int>(size))) {
      return absl::DataLossError("corrupt result chunk");
    }
    at += size;
  }
  return chunks;
}

}  // namespace radflux
