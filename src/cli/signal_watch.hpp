// Termination signals (Ctrl-C, SIGTERM, a closed terminal) taken by a thread of our own, so a
// live machine can be stopped in order rather than killed mid-move.
#pragma once

#include <pthread.h>

#include <atomic>
#include <csignal>  // sigtimedwait
#include <functional>
#include <thread>

namespace gantry {

// SIGINT, SIGTERM, SIGHUP and SIGQUIT are blocked from construction on, in this thread and in
// every thread started after (the controller's: construct this first), and taken by one
// watcher thread, which calls `on_signal` from an ordinary thread (a signal handler could not
// E-stop: that takes a lock). stop() ends the watcher at once (it wakes it with kWake, which
// the watcher takes and drops; waiting out the wait's period made every command 100 ms
// slower, `gantry check` on a one-line file 0.11 s); the destructor restores the mask.
class SignalWatch {
 public:
  SignalWatch() {
    sigemptyset(&set_);
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, kWake}) sigaddset(&set_, s);
    pthread_sigmask(SIG_BLOCK, &set_, &old_);
  }
  ~SignalWatch() {
    stop();
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SignalWatch(const SignalWatch&) = delete;
  SignalWatch& operator=(const SignalWatch&) = delete;
  void start(std::function<void(int)> on_signal) {
    thread_ = std::thread([this, f = std::move(on_signal)] {
      const timespec period{0, 100'000'000};
      while (!done_) {
        const int sig = sigtimedwait(&set_, nullptr, &period);
        if (sig > 0 && sig != kWake) f(sig);
      }
    });
  }
  void stop() {
    done_ = true;
    if (!thread_.joinable()) return;
    pthread_kill(thread_.native_handle(), kWake);  // pending until its next wait, if not in one
    thread_.join();
  }

 private:
  static constexpr int kWake = SIGUSR1;
  sigset_t set_{}, old_{};
  std::atomic<bool> done_{false};
  std::thread thread_;
};

}  // namespace gantry
