// The record set of a batch: list file (path scale [label], # comments, paths relative to
// the list file) and folder mode; errors name the file and line.
#include "run_process.h"
#include "server/batch/batch.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

namespace fs = std::filesystem;
using server::BatchInputError;
using server::load_record_set;

std::string error_of(const std::string& spec) {
  try {
    load_record_set(spec);
  } catch (const BatchInputError& e) {
    return e.what();
  }
  return "";
}

TEST(RecordSet, ListFileReadsPathsScalesLabelsAndSkipsComments) {
  const std::string dir = test_support::fresh_temp_dir("set-list");
  test_support::write_text(dir + "/list.txt",
                           "# DBE and MCE of one record\n"
                           "\n"
                           "recs/a.AT2   1.0          # DBE\n"
                           "recs/a.AT2   1.5   a-MCE\r\n"
                           "  /abs/b.txt 0.75\n");
  const auto set = load_record_set(dir + "/list.txt");
  ASSERT_EQ(set.size(), 3u);
  EXPECT_EQ(set[0].path, dir + "/recs/a.AT2");  // relative to the list file, not the cwd
  EXPECT_EQ(set[0].shown, "recs/a.AT2");
  EXPECT_EQ(set[0].scale, 1.0);
  EXPECT_EQ(set[0].label, "a");
  EXPECT_EQ(set[0].line, 3);
  EXPECT_EQ(set[1].scale, 1.5);
  EXPECT_EQ(set[1].label, "a-MCE");
  EXPECT_EQ(set[2].path, "/abs/b.txt");
  EXPECT_EQ(set[2].label, "b_x0.75");  // default label names a scale other than 1
}

TEST(RecordSet, FolderTakesRecordFilesSortedByName) {
  const std::string dir = test_support::fresh_temp_dir("set-folder");
  for (const char* f : {"z.AT2", "a.at2", "m.txt", "c.csv", "README.md", "notes.yaml"})
    test_support::write_text(dir + "/" + f, "x\n");
  fs::create_directories(dir + "/sub.AT2");  // a folder is not a record
  const auto set = load_record_set(dir);
  ASSERT_EQ(set.size(), 4u);
  EXPECT_EQ(set[0].shown, "a.at2");
  EXPECT_EQ(set[1].shown, "c.csv");
  EXPECT_EQ(set[2].shown, "m.txt");
  EXPECT_EQ(set[3].shown, "z.AT2");
  for (const auto& r : set) EXPECT_EQ(r.scale, 1.0);
  EXPECT_EQ(set[3].label, "z");
}

TEST(RecordSet, SameStemInFolderGetsDistinctLabels) {
  const std::string dir = test_support::fresh_temp_dir("set-stem");
  test_support::write_text(dir + "/x.AT2", "x\n");
  test_support::write_text(dir + "/x.csv", "x\n");
  const auto set = load_record_set(dir);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_NE(set[0].label, set[1].label);
}

TEST(RecordSet, BadListLinesAreErrorsNamingFileAndLine) {
  const std::string dir = test_support::fresh_temp_dir("set-bad");
  test_support::write_text(dir + "/noscale.txt", "# c\na.AT2\n");
  EXPECT_NE(error_of(dir + "/noscale.txt").find("noscale.txt:2"), std::string::npos) << error_of(dir + "/noscale.txt");
  test_support::write_text(dir + "/badscale.txt", "a.AT2 1.0\nb.AT2 abc\n");
  EXPECT_NE(error_of(dir + "/badscale.txt").find("badscale.txt:2: scale factor 'abc'"), std::string::npos);
  test_support::write_text(dir + "/negscale.txt", "a.AT2 -1\n");
  EXPECT_NE(error_of(dir + "/negscale.txt").find("outside"), std::string::npos);
  test_support::write_text(dir + "/nanscale.txt", "a.AT2 nan\n");
  EXPECT_NE(error_of(dir + "/nanscale.txt").find("nanscale.txt:1"), std::string::npos);
  test_support::write_text(dir + "/dup.txt", "a.AT2 1\nother/a.AT2 1\n");
  EXPECT_NE(error_of(dir + "/dup.txt").find("label 'a' is used twice"), std::string::npos) << error_of(dir + "/dup.txt");
  test_support::write_text(dir + "/badlabel.txt", "a.AT2 1 ../x\n");
  EXPECT_NE(error_of(dir + "/badlabel.txt").find("label '../x'"), std::string::npos);
  test_support::write_text(dir + "/partial.txt", "a.AT2 1 x.partial\n");
  EXPECT_NE(error_of(dir + "/partial.txt").find("x.partial"), std::string::npos);
  test_support::write_text(dir + "/extra.txt", "a b.AT2 1 x\n");
  EXPECT_NE(error_of(dir + "/extra.txt").find("4 fields"), std::string::npos);
  test_support::write_text(dir + "/empty.txt", "# nothing\n\n");
  EXPECT_NE(error_of(dir + "/empty.txt").find("names no records"), std::string::npos);
  EXPECT_NE(error_of(dir + "/nonexistent").find("no such file"), std::string::npos);
  test_support::write_text(dir + "/one.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\n");
  EXPECT_NE(error_of(dir + "/one.AT2").find("is a record, not a record list"), std::string::npos);
  fs::create_directories(dir + "/emptyfolder");
  EXPECT_NE(error_of(dir + "/emptyfolder").find("no record files"), std::string::npos);
}

TEST(RecordSet, MissingRecordFileIsNotASetErrorItsRunFails) {
  const std::string dir = test_support::fresh_temp_dir("set-missing");
  test_support::write_text(dir + "/list.txt", "missing.AT2 1\n");
  EXPECT_EQ(load_record_set(dir + "/list.txt").size(), 1u);
}

}  // namespace
