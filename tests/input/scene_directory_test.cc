// Hostile scenes: a scene named files outside its own directory (an absolute uri, "../", a
// symlink, /proc/self/environ) and the readers read them, so their bytes could come back out in
// lit.glb, the job store and `fetch`. Every file a scene names must now lie inside the scene
// file's directory tree (input/scene_directory.h).
#include "input/scene_directory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "input/scene_loader.h"
#include "testing/temp_dir.h"
#include "tests/input/gltf_fixture.h"

namespace radfarm {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// A tree for a scene in TOP/scene/, with a file beside it outside its directory (TOP/secret.bin,
// TOP/secret.mtl) and one in a nested directory (TOP/scene/sub/).
class HostileTree {
 public:
  HostileTree() {
    fs::create_directories(scene_dir() + "/sub");
    Write(top_.File("secret.bin"), std::string(64, 's'));
    Write(top_.File("secret.mtl"), "newmtl glow\nKd 0.5 0.5 0.5\nKe 1 1 1\n");
  }

  std::string top() const { return top_.path(); }
  std::string scene_dir() const { return top_.File("scene"); }
  std::string InScene(const std::string& name) const { return scene_dir() + "/" + name; }

  // "../" repeated up to the root from the scene's directory, then `path` (without its leading
  // "/"): a relative name that climbs to an absolute one.
  std::string Climbing(const std::string& path) const {
    std::string up;
    for (const auto& part : fs::path(scene_dir()).relative_path()) {
      if (!part.empty()) up += "../";
    }
    return up + path.substr(1);
  }

  void Link(const std::string& name, const std::string& target) const {
    fs::create_symlink(target, InScene(name));
  }

  static void Write(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
  }

 private:
  TempDir top_;
};

std::string SceneLoadError(const std::string& path) {
  Result<InputScene> scene = LoadScene(path);
  EXPECT_FALSE(scene.ok()) << path << " loaded but should not have";
  return scene.ok() ? "" : scene.error();
}

// FloorAndLight written to TOP/scene/s.gltf with one more buffer (its 64 bytes at `uri`).
std::string GltfWithBuffer(const HostileTree& tree, const std::string& uri) {
  const std::string path = testing::FloorAndLight().WriteGltf(tree.InScene("s.gltf"));
  nlohmann::json doc = nlohmann::json::parse(testing::ReadFile(path));
  doc["buffers"].push_back({{"byteLength", 64}, {"uri", uri}});
  std::ofstream(path, std::ios::trunc) << doc.dump(1);
  return path;
}

// FloorAndLight written to TOP/scene/s.gltf with one image file at `uri` (used by no texture:
// tinygltf reads every image).
std::string GltfWithImage(const HostileTree& tree, const std::string& uri) {
  testing::GltfFixture f = testing::FloorAndLight();
  f.json()["images"] = {{{"uri", uri}}};
  return f.WriteGltf(tree.InScene("s.gltf"));
}

// An OBJ lit by the library `mtllib` names, on its first line.
std::string ObjWithLibrary(const HostileTree& tree, const std::string& mtllib) {
  const std::string path = tree.InScene("s.obj");
  HostileTree::Write(path,
                     "mtllib " + mtllib + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glow\nf 1 2 3\n");
  return path;
}

// An OBJ whose library, TOP/scene/lit.mtl, names `map` on its line 3.
std::string ObjWithTextureMap(const HostileTree& tree, const std::string& map) {
  HostileTree::Write(tree.InScene("lit.mtl"),
                     "newmtl glow\nKd 0.5 0.5 0.5\nmap_Kd " + map + "\nKe 1 1 1\n");
  return ObjWithLibrary(tree, "lit.mtl");
}

constexpr const char* kLeadsOutside = "leads outside the scene's directory ";
constexpr const char* kNotSceneData = "; files under /proc, /sys and /dev are not scene data";

void ExpectMentions(const std::string& error, const std::string& part) {
  EXPECT_NE(error.find(part), std::string::npos) << "'" << part << "' not in: " << error;
}

TEST(SceneDirectoryTest, ResolvesNamesInsideTheTreeAndRefusesTheRest) {
  HostileTree tree;
  const SceneDirectory scene(tree.InScene("s.gltf"));
  EXPECT_EQ(scene.root(), fs::canonical(tree.scene_dir()));
  Result<fs::path> nested = scene.Resolve("sub/../sub/a.bin");
  ASSERT_TRUE(nested.ok()) << nested.error();
  EXPECT_EQ(*nested, scene.root() / "sub/a.bin");
  // Relative to a directory inside the tree (an MTL's), still held to the root.
  EXPECT_TRUE(scene.Resolve("../a.png", scene.root() / "sub").ok());
  EXPECT_FALSE(scene.Resolve("../../a.png", scene.root() / "sub").ok());
  EXPECT_EQ(scene.Resolve("/etc/passwd").error().rfind("is an absolute path; ", 0), 0u);
  EXPECT_EQ(scene.Resolve("").error(), "is empty");
  ExpectMentions(scene.Resolve("../secret.bin").error(), kLeadsOutside);
  // A directory whose name starts like the root's is not inside it.
  EXPECT_FALSE(scene.Resolve("../scene2/a.bin").ok());
}

TEST(SceneDirectoryTest, GltfBuffersMayNotLeaveTheScenesDirectory) {
  HostileTree tree;
  const std::string secret = tree.top() + "/secret.bin";
  std::string path = GltfWithBuffer(tree, secret);
  ExpectMentions(SceneLoadError(path),
                 path + ": buffers[1].uri '" + secret + "' is an absolute path; ");
  path = GltfWithBuffer(tree, "../secret.bin");
  ExpectMentions(SceneLoadError(path), path + ": buffers[1].uri '../secret.bin' " + kLeadsOutside);
  tree.Link("link.bin", secret);
  path = GltfWithBuffer(tree, "link.bin");
  ExpectMentions(SceneLoadError(path), path + ": buffers[1].uri 'link.bin' " + kLeadsOutside);
  // tinygltf decodes %2e%2e to "..".
  path = GltfWithBuffer(tree, "%2e%2e/secret.bin");
  ExpectMentions(SceneLoadError(path), path + ": buffers[1].uri '../secret.bin' " + kLeadsOutside);
  // /proc/self/environ passes for a regular file of size 0.
  path = GltfWithBuffer(tree, tree.Climbing("/proc/self/environ"));
  ExpectMentions(SceneLoadError(path), kNotSceneData);
  tree.Link("env.bin", "/proc/self/environ");
  path = GltfWithBuffer(tree, "env.bin");
  ExpectMentions(SceneLoadError(path), path + ": buffers[1].uri 'env.bin' leads to /proc/");
}

TEST(SceneDirectoryTest, GltfImagesMayNotLeaveTheScenesDirectory) {
  HostileTree tree;
  const std::string secret = tree.top() + "/secret.bin";
  std::string path = GltfWithImage(tree, secret);
  ExpectMentions(SceneLoadError(path),
                 path + ": images[0].uri '" + secret + "' is an absolute path; ");
  path = GltfWithImage(tree, "../secret.bin");
  ExpectMentions(SceneLoadError(path), path + ": images[0].uri '../secret.bin' " + kLeadsOutside);
  tree.Link("link.png", secret);
  path = GltfWithImage(tree, "link.png");
  ExpectMentions(SceneLoadError(path), path + ": images[0].uri 'link.png' " + kLeadsOutside);
  path = GltfWithImage(tree, tree.Climbing("/proc/self/environ"));
  ExpectMentions(SceneLoadError(path), kNotSceneData);
}

TEST(SceneDirectoryTest, GltfFilesInANestedDirectoryStillLoad) {
  HostileTree tree;
  HostileTree::Write(tree.InScene("sub/part.bin"), std::string(64, 'p'));
  const std::vector<uint8_t> bmp = testing::BmpImage(1, 1, {10, 20, 30});
  HostileTree::Write(tree.InScene("sub/tex.bmp"), std::string(bmp.begin(), bmp.end()));
  // A symlink that stays inside the tree is followed.
  tree.Link("inside.bin", "sub/part.bin");
  testing::GltfFixture f = testing::FloorAndLight();
  f.json()["images"] = {{{"uri", "sub/tex.bmp"}}};
  const std::string path = f.WriteGltf(tree.InScene("s.gltf"));
  nlohmann::json doc = nlohmann::json::parse(testing::ReadFile(path));
  doc["buffers"].push_back({{"byteLength", 64}, {"uri", "sub/part.bin"}});
  doc["buffers"].push_back({{"byteLength", 64}, {"uri", "sub/../inside.bin"}});
  std::ofstream(path, std::ios::trunc) << doc.dump(1);
  Result<InputScene> scene = LoadScene(path);
  EXPECT_TRUE(scene.ok()) << scene.error();
}

TEST(SceneDirectoryTest, ObjLibrariesMayNotLeaveTheScenesDirectory) {
  HostileTree tree;
  const std::string secret = tree.top() + "/secret.mtl";
  std::string path = ObjWithLibrary(tree, secret);
  ExpectMentions(SceneLoadError(path), path + ":1: mtllib '" + secret + "' is an absolute path; ");
  path = ObjWithLibrary(tree, "../secret.mtl");
  ExpectMentions(SceneLoadError(path), path + ":1: mtllib '../secret.mtl' " + kLeadsOutside);
  tree.Link("link.mtl", secret);
  path = ObjWithLibrary(tree, "link.mtl");
  ExpectMentions(SceneLoadError(path), path + ":1: mtllib 'link.mtl' " + kLeadsOutside);
  path = ObjWithLibrary(tree, tree.Climbing("/proc/self/environ"));
  ExpectMentions(SceneLoadError(path), kNotSceneData);
}

// Texture maps are never read, so a path that leaves the tree (an exporter's absolute one) only
// draws the warning that MTL textures are ignored.
TEST(SceneDirectoryTest, MtlTextureMapsAreNeverReadSoTheirPathsAreNotRefused) {
  HostileTree tree;
  const std::string secret = tree.top() + "/secret.bin";
  for (const std::string& map :
       {secret, std::string("../secret.bin"), tree.Climbing("/proc/self/environ")}) {
    SCOPED_TRACE(map);
    Result<InputScene> scene = LoadScene(ObjWithTextureMap(tree, map));
    ASSERT_TRUE(scene.ok()) << scene.error();
    bool ignored = false;
    for (const std::string& w : scene->warnings) {
      ignored |= w.find("'map_Kd' ignored") != std::string::npos;
    }
    EXPECT_TRUE(ignored);
  }
}

// A library in a subdirectory loads.
TEST(SceneDirectoryTest, ObjFilesInANestedDirectoryStillLoad) {
  HostileTree tree;
  HostileTree::Write(tree.InScene("sub/lit.mtl"),
                     "newmtl glow\nKd 0.5 0.5 0.5\nmap_Kd ../tex.png\nKe 1 1 1\n");
  Result<InputScene> scene = LoadScene(ObjWithLibrary(tree, "sub/lit.mtl"));
  ASSERT_TRUE(scene.ok()) << scene.error();
  EXPECT_EQ(scene->materials[0].name, "glow");
}

// A user who trusts a scene lets it read files elsewhere (--allow-outside-files): absolute and
// climbing names load; the kernel's and devices' files stay refused.
TEST(SceneDirectoryTest, AllowedOutsideFilesLoadButSystemFilesStayRefused) {
  HostileTree tree;
  const SceneDirectory anywhere(tree.InScene("s.gltf"), FileReach::kAnywhere);
  const std::string secret = tree.top() + "/secret.bin";
  Result<fs::path> absolute = anywhere.Resolve(secret);
  ASSERT_TRUE(absolute.ok()) << absolute.error();
  EXPECT_EQ(*absolute, fs::canonical(secret));
  EXPECT_TRUE(anywhere.Resolve("../secret.bin").ok());
  ExpectMentions(anywhere.Resolve("/proc/self/environ").error(), kNotSceneData);
  ExpectMentions(anywhere.Resolve(tree.Climbing("/dev/zero")).error(), kNotSceneData);

  for (const std::string& uri : {secret, std::string("../secret.bin")}) {
    SCOPED_TRACE(uri);
    const std::string path = GltfWithBuffer(tree, uri);
    EXPECT_FALSE(LoadScene(path).ok());
    Result<InputScene> scene = LoadScene(path, kDefaultMaxInputFileBytes, 0, FileReach::kAnywhere);
    EXPECT_TRUE(scene.ok()) << scene.error();
  }
  const std::string obj = ObjWithLibrary(tree, "../secret.mtl");
  EXPECT_FALSE(LoadScene(obj).ok());
  Result<InputScene> lit = LoadScene(obj, kDefaultMaxInputFileBytes, 0, FileReach::kAnywhere);
  ASSERT_TRUE(lit.ok()) << lit.error();
  const std::string env = GltfWithBuffer(tree, tree.Climbing("/proc/self/environ"));
  Result<InputScene> refused = LoadScene(env, kDefaultMaxInputFileBytes, 0, FileReach::kAnywhere);
  ASSERT_FALSE(refused.ok());
  ExpectMentions(refused.error(), kNotSceneData);
}

// Between the check of a name and the read of its file, a directory on the way may be swapped
// for a symlink to elsewhere: the read checks where the file it opened really lies. (The swap is
// made before Read here: the path Resolve gave, TOP/scene/sub/secret.bin, now runs through a
// symlink to TOP.)
TEST(SceneDirectoryTest, AReadChecksWhereTheOpenedFileLies) {
  HostileTree tree;
  const SceneDirectory scene(tree.InScene("s.gltf"));
  HostileTree::Write(tree.InScene("sub/secret.bin"), "inside");
  Result<fs::path> resolved = scene.Resolve("sub/secret.bin");
  ASSERT_TRUE(resolved.ok()) << resolved.error();
  Result<std::string> read = scene.Read(*resolved, 1024);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(*read, "inside");

  fs::remove_all(tree.InScene("sub"));
  fs::create_directory_symlink(tree.top(), tree.InScene("sub"));
  read = scene.Read(*resolved, 1024);
  ASSERT_FALSE(read.ok()) << "read " << *read;
  ExpectMentions(read.error(), resolved->string() +
                                   ": is reached through a symlink that now leads " +
                                   "outside the scene's directory ");
  // Allowed to reach anywhere, the same read goes on; the kernel's files stay refused.
  const SceneDirectory anywhere(tree.InScene("s.gltf"), FileReach::kAnywhere);
  read = anywhere.Read(*resolved, 1024);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(*read, std::string(64, 's'));
  fs::remove(tree.InScene("sub"));
  fs::create_directory_symlink("/proc/self", tree.InScene("sub"));
  const fs::path environ = scene.root() / "sub/environ";
  read = anywhere.Read(environ, 1 << 20);
  ASSERT_FALSE(read.ok());
  ExpectMentions(read.error(), kNotSceneData);
}

}  // namespace
}  // namespace radfarm
