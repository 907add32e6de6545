// Hardware faults of the program become faults of its task (issue 14): a SIGSEGV,
// SIGBUS, SIGFPE or SIGILL raised while a task activation runs generated code, or
// a native it called, is reported like any runtime fault (kind, site, callers,
// task, cycle); the task's activation is abandoned and the other tasks go on
// (docs/vm.md, "Faults").  Anywhere else the signal keeps its default action.
#pragma once

namespace stc::vm {

// Installs the handlers (once per process) and an alternate signal stack for the
// calling thread (once per thread), so that a stack overflow can be reported too.
void installFaultSignals();

}  // namespace stc::vm
