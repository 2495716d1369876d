#pragma once
// The one door for reading a transfer file of any kind: a .prt file (transfer_file.h: per vertex or per
// lightmap texel, diffuse or glossy) or a .cprt file (cprt_file.h: its CPCA model, per vertex or per
// texel), told apart by their magic, not their name. Every command that reads transfer (render, view,
// shade) opens it here and decides from what the file holds.
#include <string>
#include <variant>
#include <vector>

#include <glm/vec3.hpp>

#include "compress/compressed.h"
#include "mesh/mesh.h"
#include "transfer/transfer_file.h"

namespace prt::compress {

/// What a transfer file holds.
struct TransferFile {
  std::string path;
  /// The transfer itself (.prt), or its CPCA model (.cprt).
  std::variant<transfer::TransferData, CompressedTransfer> contents;
  /// A prt engine glTF (.glb, gltf_transfer.h): the albedo baked into each vertex's transfer
  /// (_PRT_ALBEDO), which the mesh loaded from the same file must shade with; empty for other files.
  std::vector<glm::vec3> baked_albedo;

  bool compressed() const { return std::holds_alternative<CompressedTransfer>(contents); }
  /// The header of the transfer the file stands for (a model's: its source header with a float32
  /// payload, as decompress gives it).
  transfer::Header header() const;
};

/// Reads and checks the whole file (transfer::read_transfer, read_cprt, or read_gltf_transfer for a
/// glTF binary: its CPCA model). Throws prt::Error("<path>: <problem>").
TransferFile open_transfer(const std::string& path);

/// Gives `mesh` the file's baked albedo, if it has one (a prt engine glTF) and the mesh has as many
/// vertices; call after checking that the transfer belongs to the mesh.
void use_baked_albedo(const TransferFile& file, mesh::Mesh* mesh);

/// The transfer the file stands for: its data, or its model decompressed (what `prt shade` shades, the
/// CPU reference of compressed transfer).
transfer::TransferData expand(TransferFile file);

}  // namespace prt::compress
