// The models of `binpick detect` (host/app/detect_models.hpp): which obj_id each --model gets,
// the order of several, and one clear refusal for every ambiguity.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "host/app/detect_models.hpp"
#include "host/core/error.hpp"
#include "tests/support/cli_run.hpp"

using namespace binpick;
using namespace binpick::cli;
namespace fs = std::filesystem;

namespace {

fs::path touch(const fs::path& path) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "x";
  return path;
}

// The message of the InputError resolve_model_sources throws ("" if none).
std::string refusal(const std::vector<std::string>& models, const std::vector<int>& obj_ids) {
  try {
    resolve_model_sources(models, obj_ids);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DetectModels, ObjIdOfBopName) {
  EXPECT_EQ(obj_id_of_name("a/obj_000012.ppfm"), 12);
  EXPECT_EQ(obj_id_of_name("obj_000001.ply"), 1);
  EXPECT_FALSE(obj_id_of_name("obj_000000.ppfm"));
  EXPECT_FALSE(obj_id_of_name("obj_12.ppfm"));
  EXPECT_FALSE(obj_id_of_name("obj_-00001.ppfm"));
  EXPECT_FALSE(obj_id_of_name("bracket.ppfm"));
}

TEST(DetectModels, ObjIdsFromOptionsNamesOrTheSingleDefault) {
  const fs::path dir = test::fresh_temp_dir("detect_models_ids");
  const std::string a = touch(dir / "bracket.ppfm").string(), b = touch(dir / "tee.ppfm").string();
  const std::string named = touch(dir / "obj_000007.ppfm").string();

  auto s = resolve_model_sources({a}, {});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].obj_id, 1);
  EXPECT_EQ(resolve_model_sources({named}, {})[0].obj_id, 7);
  EXPECT_EQ(resolve_model_sources({a}, {4})[0].obj_id, 4);
  // Ascending by obj_id, whatever the order given.
  s = resolve_model_sources({a, b, named}, {9, 2, 7});
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].path, b);
  EXPECT_EQ(s[1].obj_id, 7);
  EXPECT_EQ(s[2].path, a);
  fs::remove_all(dir);
}

TEST(DetectModels, DirectoryOfModelsOrBopModelsFolder) {
  const fs::path dir = test::fresh_temp_dir("detect_models_dir");
  touch(dir / "ppfm/obj_000002.ppfm");
  touch(dir / "ppfm/obj_000001.ppfm");
  touch(dir / "ppfm/notes.txt");
  auto s = resolve_model_sources({(dir / "ppfm").string()}, {});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].obj_id, 1);
  EXPECT_EQ(s[1].path, dir / "ppfm/obj_000002.ppfm");

  // A BOP models/ folder: the meshes, by their names.
  touch(dir / "models/models_info.json");
  touch(dir / "models/obj_000003.ply");
  touch(dir / "models/obj_000001.ply");
  s = resolve_model_sources({(dir / "models").string()}, {});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].path, dir / "models/obj_000001.ply");
  EXPECT_EQ(s[1].obj_id, 3);
  // A directory beside a file.
  const std::string tee = touch(dir / "obj_000005.ppfm").string();
  s = resolve_model_sources({tee, (dir / "ppfm").string()}, {});
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[2].obj_id, 5);
  fs::remove_all(dir);
}

TEST(DetectModels, AmbiguitiesAreRefusedInOneMessage) {
  const fs::path dir = test::fresh_temp_dir("detect_models_refused");
  const std::string a = touch(dir / "bracket.ppfm").string(), b = touch(dir / "tee.ppfm").string();
  const std::string one = touch(dir / "obj_000001.ppfm").string();
  fs::create_directories(dir / "empty");
  touch(dir / "loose/bracket.ppfm");

  EXPECT_NE(refusal({a, b}, {}).find("cannot tell the obj_id of --model " + a), std::string::npos);
  EXPECT_NE(refusal({a, b}, {1}).find("2 --model but 1 --obj-id"), std::string::npos);
  EXPECT_NE(refusal({a, b}, {3, 3}).find("two models have obj_id 3"), std::string::npos);
  EXPECT_NE(refusal({a, one}, {1, 1}).find("two models have obj_id 1"), std::string::npos);
  EXPECT_NE(refusal({one, a}, {}).find("cannot tell the obj_id"), std::string::npos);
  EXPECT_NE(refusal({one}, {2}).find("--obj-id 2 contradicts the name"), std::string::npos);
  EXPECT_NE(refusal({a}, {0}).find("--obj-id 0 must be at least 1"), std::string::npos);
  EXPECT_NE(refusal({(dir / "empty").string()}, {}).find("holds no model"), std::string::npos);
  EXPECT_NE(refusal({(dir / "empty").string()}, {1}).find("for the directory"), std::string::npos);
  EXPECT_NE(refusal({(dir / "loose").string()}, {}).find("cannot tell the obj_id of bracket.ppfm"),
            std::string::npos);
  EXPECT_NE(refusal({(dir / "nope.ppfm").string()}, {}).find("file not found"), std::string::npos);
  // Two models of one obj_id, one from a name and one from a directory.
  touch(dir / "dir/obj_000001.ppfm");
  EXPECT_NE(refusal({one, (dir / "dir").string()}, {}).find("two models have obj_id 1"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
