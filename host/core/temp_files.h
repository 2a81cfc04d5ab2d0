// The temporary files of outputs being written (core/file_output.h), removed when the process is
// interrupted: a small registry a signal handler can read without allocating or locking.
#pragma once

namespace vkray::temp_files {

// Records `absolutePath` as a live temporary file; returns the slot for untrack(), or -1 when the
// path is too long or every slot is taken (the file is then written unprotected, and only an
// interruption can leave it behind). Installs the handler of installInterruptCleanup() first.
int track(const char* absolutePath);
// Forgets a slot of track() (nothing for -1): the file was renamed into place or removed.
void untrack(int slot);

// Makes SIGINT, SIGTERM and SIGHUP remove every tracked file, then end the process with the
// signal's default action (so the exit status is the signal's). Only a signal whose disposition is
// the default is taken over: one a program ignores (nohup) stays ignored, and one it handles itself
// stays its own (its handler decides how to stop, and the writers' destructors remove their files on
// the way out). Idempotent; track() calls it each time, as a disposition may change after the first
// file (a forked child resetting it, a program installing its own).
void installInterruptCleanup();

}  // namespace vkray::temp_files
