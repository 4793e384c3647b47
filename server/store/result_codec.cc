#include "server/store/result_codec.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "absl/strings/str_cat.h"
#include "google/protobuf/io/coded_stream.h"

namespace radflux {

namespace {

// MakeResultChunks; without B (and I) when `radiosity` is null, without I when `indirect` is
// null or empty.
std::vector<v1::ResultChunk> MakeChunks(const PatchMesh& mesh, const std::vector<Rgb>* radiosity,
                                        const std::vector<Rgb>* indirect,
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
      if (radiosity == nullptr) continue;
      for (double b : (*radiosity)[i]) p->add_radiosity(b);
      if (indirect == nullptr || indirect->empty()) continue;
      for (double b : (*indirect)[i]) p->add_indirect(b);
    }
  }
  chunks.emplace_back().set_report_json(report_json);
  return chunks;
}

}  // namespace

std::vector<v1::ResultChunk> MakeResultChunks(const PatchMesh& mesh, const SolveResult& solve,
                                              const std::vector<Rgb>& indirect,
                                              const std::string& report_json) {
  return MakeChunks(mesh, &solve.radiosity, &indirect, report_json);
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

namespace {

using google::protobuf::io::CodedOutputStream;

// Appends `value` as a protobuf varint.
void AppendVarint(std::string& out, uint64_t value) {
  uint8_t varint[10];
  const uint8_t* end = CodedOutputStream::WriteVarint64ToArray(value, varint);
  out.append(reinterpret_cast<const char*>(varint), static_cast<size_t>(end - varint));
}

// Wire tags (field number << 3 | 2, length-delimited) of ResultChunk.patches,
// PatchChunk.radiosity and PatchChunk.indirect; these two are PatchChunk's last fields, so
// protobuf writes them last, in this order.
constexpr char kPatchesTag = (3 << 3) | 2;
constexpr char kRadiosityTag = (4 << 3) | 2;
constexpr char kIndirectTag = (5 << 3) | 2;

// Appends the length prefix of EncodeResultChunks.
void AppendSize(std::string& out, uint64_t size) {
  out.append(reinterpret_cast<const char*>(&size), sizeof(size));
}

}  // namespace

ResultEncoder::ResultEncoder(const PatchMesh& mesh) : patch_count_(mesh.size()) {
  // The chunks without B: the header and vertex chunks whole, the patch chunks' other fields.
  const std::vector<v1::ResultChunk> chunks = MakeChunks(mesh, nullptr, nullptr, "");
  std::string bytes;
  for (const v1::ResultChunk& chunk : chunks) {
    if (chunk.part_case() == v1::ResultChunk::kReportJson) break;
    if (!chunk.has_patches()) {
      const std::string encoded = chunk.SerializeAsString();
      AppendSize(bytes, encoded.size());
      bytes += encoded;
      continue;
    }
    const v1::PatchChunk& p = chunk.patches();
    const uint64_t b_bytes = sizeof(double) * kBands * static_cast<uint64_t>(p.source_face_size());
    const std::string fields = p.SerializeAsString();  // first_patch, vertices, source_face
    const uint64_t field = 1 + CodedOutputStream::VarintSize64(b_bytes) + b_bytes;  // B or I
    const uint64_t inner = fields.size() + 2 * field;
    AppendSize(bytes, 1 + CodedOutputStream::VarintSize64(inner) + inner);
    bytes.push_back(kPatchesTag);
    AppendVarint(bytes, inner);
    bytes += fields;
    bytes.push_back(kRadiosityTag);
    AppendVarint(bytes, b_bytes);
    before_b_.push_back(std::move(bytes));
    bytes.clear();
    std::string& before_i = before_i_.emplace_back();
    before_i.push_back(kIndirectTag);
    AppendVarint(before_i, b_bytes);
  }
  before_b_.push_back(std::move(bytes));  // after the last patch chunk's B: nothing
  status_ = blob_.Append(before_b_.front());
}

absl::StatusOr<EncodedResult> ResultEncoder::Finish(const SolveResult& solve,
                                                    const std::vector<Rgb>& indirect,
                                                    const std::string& report_json) && {
  static_assert(sizeof(Rgb) == kBands * sizeof(double), "B is copied as packed doubles");
  static_assert(std::endian::native == std::endian::little, "packed doubles are little-endian");
  if (!status_.ok()) return status_;
  if (solve.radiosity.size() != patch_count_ || indirect.size() != patch_count_) {
    return absl::InvalidArgumentError(absl::StrCat("result: ", solve.radiosity.size(), " B and ",
                                                   indirect.size(), " indirect values for ",
                                                   patch_count_, " patches"));
  }
  v1::ResultChunk report;
  report.set_report_json(report_json);
  const std::string encoded_report = report.SerializeAsString();
  size_t total = sizeof(uint64_t) + encoded_report.size() + 2 * sizeof(Rgb) * patch_count_;
  for (const std::string& part : before_b_) total += part.size();
  for (const std::string& part : before_i_) total += part.size();
  EncodedResult result;
  std::string& out = result.bytes;
  out.reserve(total);
  for (size_t k = 0; k + 1 < before_b_.size(); ++k) {
    out += before_b_[k];
    const size_t first = k * kResultChunkItems;
    const size_t count = std::min(patch_count_ - first, kResultChunkItems);
    // Packed doubles are little-endian fixed64, as x86-64 stores them.
    out.append(reinterpret_cast<const char*>(solve.radiosity.data() + first), sizeof(Rgb) * count);
    out += before_i_[k];
    out.append(reinterpret_cast<const char*>(indirect.data() + first), sizeof(Rgb) * count);
  }
  out += before_b_.back();
  AppendSize(out, encoded_report.size());
  out += encoded_report;
  // The blob has before_b_[0] already: the rest is one more frame.
  if (absl::Status s = blob_.Append(std::string_view(out).substr(before_b_.front().size()));
      !s.ok()) {
    return s;
  }
  result.file = blob_.File();
  return result;
}

absl::StatusOr<std::vector<v1::ResultChunk>> DecodeResultChunks(const std::string& bytes,
                                                                bool header_and_report_only) {
  std::vector<v1::ResultChunk> chunks;
  size_t at = 0;
  for (size_t index = 0; at < bytes.size(); ++index) {
    uint64_t size = 0;
    if (bytes.size() - at < sizeof(size)) return absl::DataLossError("truncated result");
    std::memcpy(&size, bytes.data() + at, sizeof(size));
    at += sizeof(size);
    if (bytes.size() - at < size) return absl::DataLossError("truncated result");
    // MakeResultChunks' order: the header first, the report last.
    const bool wanted = !header_and_report_only || index == 0 || at + size == bytes.size();
    if (wanted &&
        !chunks.emplace_back().ParseFromArray(bytes.data() + at, static_cast<int>(size))) {
      return absl::DataLossError("corrupt result chunk");
    }
    at += size;
  }
  return chunks;
}

}  // namespace radflux
