// End-to-end tests of `arbor grow`: statistics, exports (OBJ/MTL, PLY, pbrt, skeleton), the up
// axis, determinism, and its refusals (bad species, absurd sizes, failed writes, inputs kept).
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "app/cli.h"

// The number after "key": in a JSON line of `grow --stats --json`.
static long long json_integer(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([0-9]+)"))) return -1;
  return std::stoll(m[1]);
}

TEST(ArborCli, GrowPrintsTheContractStatistics) {
  const CliRun r = run_arbor("grow " + species("quaking_aspen.toml") + " --seed 3 --stats --json");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* key : {"\"stems_per_level\"", "\"leaves\"", "\"curve_segments\"",
                          "\"triangles\"", "\"height\"", "\"crown_width\"", "\"seconds\""}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  }
  EXPECT_NE(r.out.find("\"stems_per_level\": [1, 50,"), std::string::npos) << r.out;
  for (const char* key : {"\"grids\": 1", "\"grid_triangles\"", "\"tension_raised_limbs\""}) {
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  }
  // The statistics alone count the geometry without building it: what only a build knows is
  // reported when -o builds it, with the same counts.
  for (const char* key : {"\"geometry_bytes\"", "\"radius_adjusted_segments\""})
    EXPECT_EQ(r.out.find(key), std::string::npos) << key << " in " << r.out;
  const std::string out = ::testing::TempDir() + "contract_stats.pbrt";
  const CliRun built =
      run_arbor("grow " + species("quaking_aspen.toml") + " --seed 3 --stats --json -o " + out);
  ASSERT_EQ(built.code, 0) << built.err;
  for (const char* key : {"\"geometry_bytes\"", "\"radius_adjusted_segments\""})
    EXPECT_NE(built.out.find(key), std::string::npos) << key << " in " << built.out;
  for (const char* key : {"curve_segments", "triangles", "grid_vertices", "leaf_cards"})
    EXPECT_EQ(json_integer(built.out, key), json_integer(r.out, key)) << key;
}

// The ramiform is in the statistics and the exports (issue 45): --stats counts the collars a
// build makes, the text says so, and the OBJ's triangles are the statistics' triangles plus the
// tubes'. Power: counting without the collars (count_tree_geometry ignoring ramiform) fails the
// equality and the text.
TEST(ArborCli, GrowCountsAndExportsTheRamiform) {
  const std::string tree = species("quaking_aspen_ramiform.toml") + " --seed 5";
  const CliRun counted = run_arbor("grow " + tree + " --json");
  ASSERT_EQ(counted.code, 0) << counted.err;
  const std::string out = ::testing::TempDir() + "ramiform.obj";
  std::remove(out.c_str());
  std::remove((::testing::TempDir() + "ramiform.mtl").c_str());
  const CliRun built = run_arbor("grow " + tree + " --json -o " + out);
  ASSERT_EQ(built.code, 0) << built.err;
  EXPECT_GT(json_integer(counted.out, "ramiforms"), 100);
  for (const char* key : {"ramiform_forks", "ramiforms", "ramiform_triangles",
                          "ramiform_trunk_forks", "ramiform_trunk_collars", "triangles"})
    EXPECT_EQ(json_integer(built.out, key), json_integer(counted.out, key)) << key;
  EXPECT_GT(
      json_integer(built.out, "mesh_triangles"),
      json_integer(built.out, "ramiform_triangles") + json_integer(built.out, "grid_triangles"));
  const CliRun text = run_arbor("grow " + tree);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("ramiforms      " +
                          std::to_string(json_integer(counted.out, "ramiforms")) + " collars at "),
            std::string::npos)
      << text.out;
  const CliRun plain = run_arbor("grow " + species("quaking_aspen.toml") + " --seed 5");
  EXPECT_EQ(plain.out.find("ramiforms"), std::string::npos) << plain.out;
  std::remove(out.c_str());
  std::remove((::testing::TempDir() + "ramiform.mtl").c_str());
}

// `grow -o tree.pbrt` keeps every limb segment as one cubic Bézier curve of 4 control points and
// positive widths, and every triangle the statistics count (trunk grid and leaves) in a mesh.
TEST(ArborCli, GrowWritesPbrtWithCurves) {
  const std::string out = ::testing::TempDir() + "tree.pbrt";
  const std::string tree = species("black_tupelo.toml") + " --quality 0.1";
  const CliRun r = run_arbor("grow " + tree + " -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const CliRun stats = run_arbor("grow " + tree + " --stats --json");
  ASSERT_EQ(stats.code, 0) << stats.err;
  const std::string text = slurp(out);
  long long curves = 0, triangles = 0;
  std::istringstream in(text);
  const std::regex curve(
      R"(Shape "curve" "string basis" "bezier" "string type" "cylinder" "point3 P" \[ ((?:\S+ ){12})\] "float width0" (\S+) "float width1" (\S+))");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (line.find("Shape \"curve\"") != std::string::npos) {
      ASSERT_TRUE(std::regex_search(line, m, curve)) << line.substr(0, 300);
      EXPECT_GT(std::stod(m[2]), 0.0);
      EXPECT_GT(std::stod(m[3]), 0.0);
      ++curves;
    } else if (const std::size_t at = line.find("\"integer indices\" ["); at != std::string::npos) {
      // Not by regex: the list holds hundreds of thousands of numbers.
      std::istringstream numbers(line.substr(at + 20, line.find(']', at) - at - 20));
      long long n = 0;
      for (long long v; numbers >> v;) ++n;
      EXPECT_EQ(n % 3, 0);
      triangles += n / 3;
    }
  }
  EXPECT_EQ(curves, json_integer(stats.out, "curve_segments"));
  EXPECT_EQ(triangles, json_integer(stats.out, "triangles"));
  EXPECT_GT(curves, 1000);
}

TEST(ArborCli, EveryShippedExampleOfEveryFormatGrowsWithStatistics) {
  for (const char* name :
       {"quaking_aspen.toml", "fractal_broadleaf.toml", "lsystem_bush.lsys", "dogwood.tmpl",
        "young_pine.tmpl", "weeping_cherry.tmpl", "young_tree.skel", "lsystem_2d_branching.lsys",
        "fractal_basic.toml", "saguaro_cactus.toml"}) {
    const CliRun r = run_arbor("grow " + species(name) + " --stats --json");
    ASSERT_EQ(r.code, 0) << name << ": " << r.err;
    for (const char* key : {"\"stems_per_level\"", "\"leaves\"", "\"curve_segments\"", "\"height\"",
                            "\"crown_width\"", "\"seconds\""}) {
      EXPECT_NE(r.out.find(key), std::string::npos) << name << " " << key;
    }
  }
}

TEST(ArborCli, SameSeedSameOutput) {
  // The same name in two folders: the OBJs (which name their .mtl) and .mtls are equal byte for
  // byte.
  const std::string a = ::testing::TempDir() + "same_seed_a/",
                    b = ::testing::TempDir() + "same_seed_b/";
  ASSERT_EQ(run_arbor("grow " + species("black_tupelo.toml") + " --quality 0.2 --seed 8 -o " + a +
                      "t.obj")
                .code,
            0);
  ASSERT_EQ(run_arbor("grow " + species("black_tupelo.toml") + " --quality 0.2 --seed 8 -o " + b +
                      "t.obj")
                .code,
            0);
  const std::string first = slurp(a + "t.obj");
  EXPECT_TRUE(first == slurp(b + "t.obj"));  // not EXPECT_EQ: no diff of 250 MB texts
  EXPECT_GT(first.size(), 1000u);
  EXPECT_EQ(slurp(a + "t.mtl"), slurp(b + "t.mtl"));
  EXPECT_NE(slurp(a + "t.mtl").find("newmtl leaf"), std::string::npos);
  for (const std::string& d : {a, b}) {
    std::remove((d + "t.obj").c_str());
    std::remove((d + "t.mtl").c_str());
  }
}

TEST(ArborCli, BadInputExitsTwoWithPosition) {
  const std::string bad = write_temp("bad.toml", "model = \"weber-penn\"\n\nShape = 12\n");
  const CliRun r = run_arbor("grow " + bad + " --stats");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find(bad + ":3:9: error: Shape = 12 is out of range"), std::string::npos)
      << r.err;

  const CliRun missing = run_arbor("grow /no/such/tree.toml --stats");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("/no/such/tree.toml: error: species does not exist"),
            std::string::npos)
      << missing.err;
  // Nothing else asked: grow reports the tree, as --stats (the README's fractal example).
  const CliRun plain = run_arbor("grow " + species("fractal_broadleaf.toml") + " --time 12");
  EXPECT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.out,
            run_arbor("grow " + species("fractal_broadleaf.toml") + " --time 12 --stats").out);
  EXPECT_NE(plain.out.find("height"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.err.find("warning"), std::string::npos) << plain.err;  // a fractal has an age
  // Options the model has no use for are said to do nothing, not ignored silently.
  const CliRun windless = run_arbor("grow " + species("saguaro_cactus.toml") + " --time 3");
  EXPECT_EQ(windless.code, 0) << windless.err;
  EXPECT_NE(windless.err.find("warning: --time 3 does nothing for " +
                              species("saguaro_cactus.toml") + ": the species has no wind"),
            std::string::npos)
      << windless.err;
  const CliRun lsystem =
      run_arbor("grow " + species("lsystem_bush.lsys") + " --quality 0.5 --time 2");
  EXPECT_EQ(lsystem.code, 0) << lsystem.err;
  EXPECT_NE(lsystem.err.find("warning: --quality 0.5 does nothing"), std::string::npos)
      << lsystem.err;
  EXPECT_NE(lsystem.err.find("warning: --time 2 does nothing"), std::string::npos) << lsystem.err;
  EXPECT_EQ(run_arbor("grow " + species("quaking_aspen.toml") + " --quality 0.5 --time 2").err,
            "");  // an aspen in the wind has both

  EXPECT_EQ(run_arbor("grow").code, 2);  // missing argument
  EXPECT_EQ(run_arbor("grow " + species("quaking_aspen.toml") + " --bogus").code, 2);
  EXPECT_EQ(run_arbor("grow " + species("quaking_aspen.toml") + " --quality 0").code, 2);
  EXPECT_EQ(run_arbor("grow " + species("quaking_aspen.toml") + " --seed -3").code, 2);
  EXPECT_EQ(run_arbor("grow " + species("quaking_aspen.toml") + " -o tree.stl").code, 2);
  EXPECT_EQ(run_arbor("frobnicate").code, 2);
  EXPECT_EQ(run_arbor("grow " + species("quaking_aspen.toml") + " --up x -o tree.obj").code, 2);
  const CliRun skel = run_arbor("grow " + species("young_tree.skel") + " --up y -o " +
                                ::testing::TempDir() + "never.skel");
  EXPECT_EQ(skel.code, 2);
  EXPECT_NE(skel.err.find("--up y: a skeleton file is arbor's own input and always z-up"),
            std::string::npos)
      << skel.err;
  EXPECT_FALSE(exists(::testing::TempDir() + "never.skel"));
}

TEST(ArborCli, GrowUpYWritesYUpMeshesWithTheirMaterials) {
  const std::string dir = ::testing::TempDir() + "cli_up_y/";
  const CliRun z = run_arbor("grow " + species("young_tree.skel") + " -o " + dir + "z.obj");
  const CliRun y = run_arbor("grow " + species("young_tree.skel") + " -o " + dir + "y.obj --up y");
  ASSERT_EQ(z.code, 0) << z.err;
  ASSERT_EQ(y.code, 0) << y.err;
  // The mesh's size is stated, so a user sees what a tree costs before opening it.
  EXPECT_NE(y.err.find("wrote " + dir + "y.obj ("), std::string::npos) << y.err;
  EXPECT_NE(y.err.find(" kB) and " + dir + "y.mtl"), std::string::npos) << y.err;
  // The same vertices turned: (x, y, z) becomes (x, z, -y); the tree's height moves to y.
  std::istringstream zs(slurp(dir + "z.obj")), ys(slurp(dir + "y.obj"));
  std::string zl, yl;
  int compared = 0;
  double top_z = 0.0, top_y = 0.0;
  while (std::getline(zs, zl) && std::getline(ys, yl)) {
    if (zl.rfind("v ", 0) != 0) continue;
    double zx, zy, zz, yx, yy, yz;
    std::sscanf(zl.c_str(), "v %lf %lf %lf", &zx, &zy, &zz);
    std::sscanf(yl.c_str(), "v %lf %lf %lf", &yx, &yy, &yz);
    EXPECT_EQ(yx, zx);
    EXPECT_EQ(yy, zz);
    EXPECT_EQ(yz, -zy);
    top_z = std::max(top_z, zz);
    top_y = std::max(top_y, yy);
    ++compared;
  }
  EXPECT_GT(compared, 100);
  EXPECT_GT(top_y, 1.0);
  EXPECT_EQ(top_y, top_z);
  EXPECT_NE(slurp(dir + "y.obj").find("mtllib y.mtl\n"), std::string::npos);
  EXPECT_NE(slurp(dir + "y.mtl").find("newmtl bark\nKd "), std::string::npos);
  const CliRun ply =
      run_arbor("grow " + species("young_tree.skel") + " -o " + dir + "y.ply --up y");
  ASSERT_EQ(ply.code, 0) << ply.err;
  EXPECT_NE(slurp(dir + "y.ply").find("y up, metres"), std::string::npos);
}

TEST(ArborCli, ObjNeverOverwritesAnInputWithItsMtl) {
  // tree.obj's .mtl is tree.mtl: here that is the species file itself (reached through a link
  // with the extension the reader wants), so nothing may be written.
  const std::string mtl = write_temp("mtl_input_tree.mtl", slurp(species("young_tree.skel")));
  const std::string link = ::testing::TempDir() + "mtl_input_link.skel";
  std::remove(link.c_str());
  ASSERT_EQ(symlink(mtl.c_str(), link.c_str()), 0);
  const std::string obj = mtl.substr(0, mtl.size() - 4) + ".obj";
  const CliRun r = run_arbor("grow " + link + " -o " + obj);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(mtl + " would overwrite the input"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(obj));
  EXPECT_EQ(slurp(mtl), slurp(species("young_tree.skel")));
}

// (That --force then grows it is WeberPenn.RefusesAbsurdSizesUnlessForced, at a limit a test can
// afford to pass.)
TEST(ArborCli, AbsurdTreesAreRefusedNamingForce) {
  const std::string huge = write_temp(
      "huge.toml",
      "model = \"weber-penn\"\nLevels = 4\n[level.1]\nBranches = 1000\n[level.2]\nBranches = "
      "1000\n[level.3]\nBranches = 1000\n");
  const CliRun r = run_arbor("grow " + huge + " --stats");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
}

TEST(ArborCli, FailedWriteExitsOneAndLeavesNoFile) {
  // A folder that cannot be made: a file stands where it would be.
  const std::string blocker = write_temp("blocker.txt", "a file, not a folder\n");
  const CliRun r =
      run_arbor("grow " + species("quaking_aspen.toml") + " -o " + blocker + "/dir/tree.obj");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("cannot write " + blocker + "/dir/tree.obj"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(blocker + "/dir/tree.obj"));
}
