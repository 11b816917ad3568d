// Held-out real-world files: the OBJ, OFF, PLY and STL models of Debian's
// assimp-testmodels, written by many exporters and never used to tune
// anything here, with the importer's own collection of broken files among
// them (empty, truncated, malformed, UTF-16, absurd counts). Every file must
// either read or be refused with an error that names it; every model read
// reconstructs to a valid boundary through all its points or is refused as
// degenerate (fewer than 4 distinct points, all in one plane).
#include "core/errors.h"
#include "core/io/mesh_io.h"
#include "reconstruct/boundary_reconstruction.h"
#include "valid_surface.h"

#include "test_support.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace scanstation {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> assimp_models() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(SCANSTATION_ASSIMP_MODELS)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && (ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl"))
      out.push_back(entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

bool in_invalid_folder(const fs::path& p) { return p.parent_path().filename() == "invalid"; }

// The mesh in `file`, or the message it was refused with (InvalidInput and
// its FormatError, IoError: the errors a user is shown).
std::variant<TriangleMesh, std::string> read_or_refusal(const fs::path& file) {
  try {
    return io::read_mesh(file);
  } catch (const InvalidInput& e) {
    return std::string(e.what());
  } catch (const IoError& e) {
    return std::string(e.what());
  }
}

TEST(AssimpModels, EveryFileReadsOrIsRefusedByName) {
  const std::vector<fs::path> files = assimp_models();
  ASSERT_GE(files.size(), 40u) << "assimp-testmodels looks incomplete";
  std::size_t read = 0, refused = 0;
  for (const fs::path& file : files) {
    const auto result = read_or_refusal(file);
    if (const auto* mesh_read = std::get_if<TriangleMesh>(&result)) {
      const TriangleMesh& mesh = *mesh_read;
      EXPECT_FALSE(in_invalid_folder(file)) << file << " was read although the importer's tests call it invalid";
      EXPECT_GT(mesh.vertices.positions.rows(), 0) << file;
      EXPECT_TRUE(mesh.vertices.positions.allFinite()) << file;
      if (mesh.faces.size() > 0) {
        EXPECT_GE(mesh.faces.minCoeff(), 0) << file;
        EXPECT_LT(mesh.faces.maxCoeff(), mesh.vertices.positions.rows()) << file;
      }
      ++read;
    } else {
      EXPECT_THAT(std::get<std::string>(result), testing::HasSubstr(file.filename().string()))
          << "the error does not name the file";
      ++refused;
    }
  }
  // Most of the collection is sound: a reader that refused it wholesale
  // would pass the loop above.
  EXPECT_GT(read, 2 * refused) << read << " read, " << refused << " refused";
}

TEST(AssimpModels, EveryModelReadReconstructsOrIsRefusedAsDegenerate) {
  std::size_t reconstructed = 0;
  for (const fs::path& file : assimp_models()) {
    const auto result = read_or_refusal(file);
    const auto* mesh = std::get_if<TriangleMesh>(&result);
    if (!mesh) continue;  // the test above checks the refusals
    try {
      const SurfaceReconstruction r = reconstruct_surface(mesh->vertices.positions, surface_defaults());
      expect_valid_surface(r, file.string());
      EXPECT_TRUE(r.statistics.all_on_boundary) << file;
      ++reconstructed;
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.find("distinct points") != std::string::npos || what.find("one plane") != std::string::npos ||
                  what.find("one line") != std::string::npos)
          << file << ": " << what;
    }
  }
  EXPECT_GE(reconstructed, 20u);
}

}  // namespace
}  // namespace scanstation
