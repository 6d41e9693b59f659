#pragma once

namespace skein {

/// OpenMP threads that sleep while they wait (issue 28, "steady under load"). libgomp's threads spin for a while
/// at every barrier; beside other work on few cores that spinning takes the cores the other work needs (on 2
/// cores a relaxation ran 4.7 to 12 times slower beside a second one). libgomp reads OMP_WAIT_POLICY once, as
/// it loads, so setting it later is too late: when the user has not chosen a policy, this sets
/// OMP_WAIT_POLICY=passive (and GOMP_SPINCOUNT=3000, a few microseconds, unless set) and executes the program
/// again with the same arguments. Call it first in main().
/// Returns normally when a policy is already set or the program cannot be executed again.
void wait_passively(char** argv);

/// The cores no other process is running on right now (the machine's running threads from /proc/loadavg, less
/// this process's own), at least 1 and at most the cores this process may use.
int free_cores();

/// A program's choice (its main()): whether the OpenMP thread count follows free_cores() while it runs, so that two
/// relaxations side by side each take the cores left to them. Off by default; OMP_NUM_THREADS, when set, wins.
/// Turned on, the calling thread's thread count follows at once.
void follow_free_cores(bool on);

/// Whether the thread count follows free_cores() (follow_free_cores(true) and no OMP_NUM_THREADS).
bool following_free_cores();

/// OMP_WAIT_POLICY as the OpenMP runtime read it ("passive" after wait_passively), or "default" when unset.
const char* wait_policy();

/// Long loops call this now and then (the yarn relaxer every half second, on the thread that runs its parallel
/// work): when follow_free_cores is on, the calling thread's next parallel regions use free_cores() threads.
void refresh_thread_count();

}  // namespace skein
