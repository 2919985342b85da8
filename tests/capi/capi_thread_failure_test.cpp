// Thread creation that fails is an error, never a hang or a crash: vpWorldCreate returns
// OutOfMemory naming the worker count, and once threads can be started again a world is created,
// stepped and destroyed as usual.
//
// The failure is real, not simulated: a forked child lowers its process limit (RLIMIT_NPROC)
// below what it already runs, so pthread_create fails with EAGAIN. The limit binds only a user
// without CAP_SYS_RESOURCE, so a child running as root first becomes the unprivileged user
// kNobody.
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "capi_test_support.h"

namespace {

constexpr uid_t kNobody = 65534;
constexpr auto kChildTimeLimit = std::chrono::seconds(60);

enum ChildExit : int {
  kPassed = 0,
  kCannotDropRoot = 10,
  kCannotLimitThreads = 11,
  kCreatedWithoutThreads = 12,
  kWrongStatus = 13,
  kCannotRaiseLimit = 14,
  kRecreateFailed = 15,
  kStepFailed = 16,
  kDestroyFailed = 17,
};

// Runs in the forked child; returns its exit code.
int createWithoutThreadsThenWith() {
  if (geteuid() == 0 && (setgid(kNobody) != 0 || setuid(kNobody) != 0)) return kCannotDropRoot;
  rlimit original{};
  if (getrlimit(RLIMIT_NPROC, &original) != 0) return kCannotLimitThreads;
  rlimit none = original;
  none.rlim_cur = 1;  // this process alone already reaches it
  if (setrlimit(RLIMIT_NPROC, &none) != 0) return kCannotLimitThreads;

  vpWorldDef def = unbudgetedWorldDef();
  def.workerCount = 4;
  vpWorldId world{};
  const vpStatus s = vpWorldCreate(&def, &world);
  if (s == vpStatus_Ok) return kCreatedWithoutThreads;
  if (s != vpStatus_OutOfMemory || !lastErrorContains("workerCount = 4")) {
    std::fprintf(stderr, "vpWorldCreate: %s: %s\n", vpStatusName(s), vpGetLastError());
    return kWrongStatus;
  }
  if (vpWorldIsValid(world) == vpStatus_Ok) return kWrongStatus;

  if (setrlimit(RLIMIT_NPROC, &original) != 0) return kCannotRaiseLimit;
  if (vpWorldCreate(&def, &world) != vpStatus_Ok) return kRecreateFailed;
  if (vpWorldLoadScene(world, VP_TEST_DATA_DIR "/scenes/tiny_world.json") != vpStatus_Ok) return kStepFailed;
  for (int i = 0; i < 3; ++i)
    if (vpWorldStep(world, 1.0f / 60.0f) != vpStatus_Ok) return kStepFailed;
  if (vpWorldDestroy(world) != vpStatus_Ok) return kDestroyFailed;
  return kPassed;
}

TEST(CApiThreadFailure, AWorldWhoseThreadsCannotStartIsOutOfMemoryAndNothingHangs) {
  std::fflush(nullptr);
  const pid_t child = fork();
  ASSERT_GE(child, 0) << "fork failed";
  if (child == 0) _exit(createWithoutThreadsThenWith());  // _exit: no atexit work in the child

  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + kChildTimeLimit;
  pid_t done = 0;
  while ((done = waitpid(child, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (done == 0) {
    kill(child, SIGKILL);
    waitpid(child, &status, 0);
    FAIL() << "the child hung: vpWorldCreate without threads did not return";
  }
  ASSERT_TRUE(WIFEXITED(status)) << "the child died by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), kPassed) << "see ChildExit for the code";
}

}  // namespace
