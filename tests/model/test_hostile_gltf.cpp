// glTF inputs from the fuzz campaign of issue 9, one test per bug: each is a clear tessera::Error naming
// the file, the JSON pointer and the reason, found before anything is allocated for it, never a crash,
// a hang or a silently wrong model. The small reproducers live in tests/model/hostile/gltf/; what is
// big or needs a variation is written here.
#include <gtest/gtest.h>

#include <string>

#include "model/model.h"
#include "model_test_util.h"

namespace tessera::model {
namespace {

using testing::errorOf;

const std::string kHostile = TESSERA_SOURCE_DIR "/tests/model/hostile/gltf/";

TEST(Gltf, AnAccessorCountOf2To32MinusOneIsRefusedBeforeAllocating) {
  // Reader::floats allocated count * 3 floats (51 GB) before it checked the bufferView's range.
  const std::string path = kHostile + "accessor-count-2to32-minus-1.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ": /accessors/0: 4294967295 elements from byteOffset 0 overrun bufferView 0 (36 bytes)");
}

TEST(Gltf, AnIndexAccessorCountOf2To31IsRefusedBeforeAllocating) {
  const std::string path = kHostile + "index-accessor-count-2to31.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }),
                  path + ": /accessors/1: 2147483648 elements from byteOffset 0 overrun bufferView 1 (12 bytes)");
}

TEST(Gltf, AnAccessorCountOf2To62IsAClearErrorNotAnInternalError) {
  // count * 3 wrapped around and std::vector threw length_error, which the CLI reports as an internal
  // error (exit 3); errorOf fails the test on anything but tessera::Error.
  const std::string path = kHostile + "accessor-count-2to62.gltf";
  EXPECT_CONTAINS(errorOf([&] { loadModel(path); }), path + ": /accessors/0: 4611686018427387904 elements");
}

}  // namespace
}  // namespace tessera::model
