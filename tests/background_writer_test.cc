// BackgroundWriter (base/background_writer.h) and OutputFiles' writes in the background: every
// task runs once, in the order added, before Wait returns; the first failure comes back (an
// exception as a Status), once; the destructor waits; and a failed background write keeps
// Commit from publishing the run.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "base/background_writer.h"
#include "base/output_files.h"

namespace pqlayout {
namespace {

namespace fs = std::filesystem;

TEST(BackgroundWriter, RunsEveryTaskOnceInOrderBeforeWaitReturns) {
  BackgroundWriter writer;
  std::vector<int> done;  // written by the writer's thread only, read after Wait
  for (int k = 0; k < 50; ++k)
    writer.Add([k, &done] {
      if (k % 10 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));  // a slow one now and then
      done.push_back(k);
      return Status::Ok();
    });
  ASSERT_TRUE(writer.Wait().ok());
  ASSERT_EQ(done.size(), 50u);
  for (int k = 0; k < 50; ++k) EXPECT_EQ(done[k], k);
  writer.Add([&done] {  // the thread goes on serving after a Wait
    done.push_back(50);
    return Status::Ok();
  });
  ASSERT_TRUE(writer.Wait().ok());
  EXPECT_EQ(done.size(), 51u);
}

TEST(BackgroundWriter, ReturnsTheFirstFailureOnceAndRunsTheRestAnyway) {
  BackgroundWriter writer;
  std::atomic<int> ran{0};
  writer.Add([&] { return ++ran, Status::Ok(); });
  writer.Add([&] { return ++ran, Status::Internal("disk full: a.csv"); });
  writer.Add([&] { return ++ran, Status::InvalidInput("b.csv"); });
  writer.Add([&]() -> Status {
    ++ran;
    throw std::runtime_error("out of memory");
  });
  const Status first = writer.Wait();
  EXPECT_EQ(ran.load(), 4);
  EXPECT_EQ(first.code(), StatusCode::kInternal);
  EXPECT_EQ(first.message(), "disk full: a.csv");
  EXPECT_TRUE(writer.Wait().ok());  // reported once
  writer.Add([]() -> Status { throw std::runtime_error("out of memory"); });
  const Status thrown = writer.Wait();
  EXPECT_EQ(thrown.code(), StatusCode::kInternal);
  EXPECT_NE(thrown.message().find("out of memory"), std::string::npos) << thrown.message();
}

TEST(BackgroundWriter, TheDestructorWaitsForTheQueue) {
  auto count = std::make_shared<std::atomic<int>>(0);
  {
    BackgroundWriter writer;
    for (int k = 0; k < 3; ++k)
      writer.Add([count] {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        ++*count;
        return Status::Ok();
      });
  }
  EXPECT_EQ(count->load(), 3);
}

// Held tasks do not start until Release; they then run in order; Wait releases too, and a
// task added after Release starts at once.
TEST(BackgroundWriter, HeldTasksStartOnlyOnceReleased) {
  BackgroundWriter writer;
  std::atomic<int> ran{0};
  writer.Hold();
  for (int k = 0; k < 3; ++k)
    writer.Add([k, &ran] {
      EXPECT_EQ(ran.load(), k);
      ++ran;
      return Status::Ok();
    });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(ran.load(), 0);
  writer.Release();
  for (int i = 0; i < 1000 && ran.load() < 3; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_EQ(ran.load(), 3);
  writer.Hold();
  writer.Add([&ran] {
    ++ran;
    return Status::Ok();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(ran.load(), 3);
  ASSERT_TRUE(writer.Wait().ok());  // releases
  EXPECT_EQ(ran.load(), 4);
}

// A writer destroyed while holding still runs what it holds (a task is never half done).
TEST(BackgroundWriter, TheDestructorRunsHeldTasks) {
  std::atomic<int> ran{0};
  {
    BackgroundWriter writer;
    writer.Hold();
    writer.Add([&ran] {
      ++ran;
      return Status::Ok();
    });
  }
  EXPECT_EQ(ran.load(), 1);
}

TEST(BackgroundWriter, WaitWithNothingAddedReturnsAtOnce) {
  BackgroundWriter writer;
  EXPECT_TRUE(writer.Wait().ok());
}

// A file written in the background is in the committed folder; a background write that fails
// keeps Commit from publishing anything, and names the file in the output folder, not staging.
TEST(OutputFilesInBackground, CommittedOnlyWhenEveryWriteSucceeded) {
  const fs::path root = fs::temp_directory_path() / ("pq_background_" + std::to_string(::getpid()));
  fs::remove_all(root);
  {
    std::unique_ptr<OutputFiles> out;
    ASSERT_TRUE(OutputFiles::Open((root / "good").string(), &out).ok());
    out->WriteInBackground([path = out->Path("fields/levelsets.csv")] {
      std::this_thread::sleep_for(std::chrono::milliseconds(30));  // still writing when Commit is called
      std::ofstream(path) << "id,phi,psi\n0,1,2\n";
      return Status::Ok();
    });
    ASSERT_TRUE(out->WriteText("report.json", "{}\n").ok());
    ASSERT_TRUE(out->Commit().ok());
    std::ifstream in(root / "good" / "fields" / "levelsets.csv");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "id,phi,psi\n0,1,2\n");
  }
  {
    std::unique_ptr<OutputFiles> out;
    ASSERT_TRUE(OutputFiles::Open((root / "bad").string(), &out).ok());
    const std::string staging = out->staging_dir();
    out->WriteInBackground([path = out->Path("fields.vtk")] { return Status::Internal(path + ": no space left"); });
    ASSERT_TRUE(out->WriteText("report.json", "{}\n").ok());
    const Status commit = out->Commit();
    EXPECT_FALSE(commit.ok());
    EXPECT_EQ(commit.message(), (root / "bad" / "fields.vtk").string() + ": no space left");
    EXPECT_FALSE(fs::exists(root / "bad" / "report.json"));
    out.reset();
    EXPECT_FALSE(fs::exists(staging));
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace pqlayout
