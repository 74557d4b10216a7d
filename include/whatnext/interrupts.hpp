// Interrupts (SIGINT, SIGTERM, SIGHUP) of a command that writes files: what they clean up, and
// how a sweep is stopped by them instead.
#pragma once

#include <functional>
#include <string>

namespace whatnext {

// Interrupts (SIGINT, SIGTERM, SIGHUP) of a command that writes files. After this call an
// interrupt removes every AtomicFile temporary in progress and every path handed to
// remove_on_interrupt(), then ends the process by that signal, as it would have ended without.
void install_interrupt_cleanup();
// Files (or empty directories) other writers make, removed on an interrupt until forgotten.
void remove_on_interrupt(const std::string& path);
void forget_on_interrupt(const std::string& path);
// Runs open, in which a writer opens a temporary by its name (PLplot, a rewrite of the file), and
// so may make the name again: an interrupt's cleanup comes wholly before it or after it, never
// between its removal of the temporary and the end of the process (a plot interrupted 0.3 s in
// left its SVG's temporary so).
void opening_by_name(const std::function<void()>& open);
// A child process that writes a temporary by its name (ffmpeg), started by start (which returns
// its process id, or -1) under the interrupts' lock: from then on an interrupt kills it, and
// waits for it, before it removes the temporaries, so that the child cannot make the name again
// after them. Forget it before waiting for it oneself. Returns start's result.
int start_writing_process(const std::function<int()>& start);
void forget_writing_process(int pid);
// While set, an interrupt only calls stop(signal) on a watcher thread (the sweep stops and writes
// what it has), once; temporaries are then cleaned up by their owners. An empty function:
// interrupts end the process again.
void set_interrupt_handler(std::function<void(int)> stop);
// Returns once every interrupt that landed before the call has reached the handler then set (the
// signal handler only queues it for the watcher thread): a handler handed over after this misses
// none of them.
void settle_interrupts();

}  // namespace whatnext
