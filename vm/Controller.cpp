#include "vm/Controller.h"

#include <algorithm>
#include <csignal>
#include <cstring>
#include <functional>
#include <map>
#include <ostream>

#include "ast/AST.h"
#include "basic/Text.h"
#include "sema/Model.h"
#include "vm/FaultSignals.h"
#include "vm/Fiber.h"
#include "vm/Image.h"
#include "vm/Jit.h"
#include "vm/Native.h"
#include "vm/Retain.h"
#include "vm/Runtime.h"

#include <csetjmp>
#include "vm/Runtime.h"
#include "vm/Scheduler.h"
#include "vm/Trace.h"

namespace stc::vm {

namespace {
// SIGINT/SIGTERM stop the run at the next tick boundary, so the retain file
// is saved and the watches are printed.
Scheduler* gStopTarget = nullptr;
extern "C" void onStopSignal(int) {
  if (gStopTarget) gStopTarget->requestStop();
}
}  // namespace

Controller::Controller(const sema::Model& model, DiagnosticsEngine& diags) : model_(model), diags_(diags) {}
Controller::~Controller() = default;

const NativeEntry* Controller::findNative(std::string_view name) const {
  for (const NativeLibrary* lib : libraries_)
    for (const NativeEntry& e : lib->natives())
      if (equalsIgnoreCase(e.name, name)) return &e;
  return nullptr;
}

bool Controller::load(std::unique_ptr<codegen::CompiledModule> module, std::string& error) {
  module_ = std::move(module);
  auto symbols = runtimeSymbols();
  for (const codegen::CompiledModule::Native& n : module_->natives) {
    const NativeEntry* e = findNative(n.name);
    if (!e) {
      error = "'" + n.name + "' is declared {attribute 'native'} but this build has no implementation of it";
      return false;
    }
    if (e->hash != n.hash) {
      error = "the native implementation of '" + n.name + "' was built for a different declaration (layout hash " + std::to_string(e->hash) +
              ", the program has " + std::to_string(n.hash) + "); rebuild it from the current ST declaration";
      return false;
    }
    symbols[n.symbol] = const_cast<void*>(e->address);
  }
  jit_ = Jit::create(*module_, symbols, error);
  if (!jit_) return false;
  image_ = static_cast<uint8_t*>(jit_->lookup("__stc_image", error));
  if (!image_) return false;
  initDynamic_ = reinterpret_cast<void (*)()>(jit_->lookup("__stc_init_dynamic", error));
  if (!initDynamic_) return false;
  fbInit_ = reinterpret_cast<void (*)(bool)>(jit_->lookup("__stc_fb_init", error));
  fbExit_ = reinterpret_cast<void (*)(bool)>(jit_->lookup("__stc_fb_exit", error));
  if (!fbInit_ || !fbExit_) return false;
  coldSnapshot_.assign(image_, image_ + module_->image.size);
  sched_ = std::make_unique<Scheduler>();
  for (const codegen::TaskPlan& plan : module_->tasks) {
    auto rt = std::make_unique<TaskRuntime>();
    for (const std::string& e : plan.entries) {
      auto fn = reinterpret_cast<void (*)()>(jit_->lookup(e, error));
      if (!fn) return false;
      rt->entries.push_back(fn);
    }
    tasks_.push_back(std::move(rt));
  }
  // Every library gets fresh state for this controller.
  sessions_.clear();
  sessionTable_.clear();
  for (const NativeLibrary* lib : libraries_)
    if (auto s = lib->newSession()) {
      sessionTable_.emplace_back(lib->sessionKey(), s.get());
      sessions_.push_back(std::move(s));
    }
  // Cold start: the constant image is already in place; the initial values
  // that did not fold are computed now.
  SessionScope scope(&sessionTable_);
  __stc_budget = INT64_MAX / 2;
  setProgramMemory(image_, module_->image.size);
  if (module_->lowMemory) {
    Fiber low(size_t{1} << 20, true);   // the 32-bit address model: locals below 4 GiB
    low.start([this] { initDynamic_(); });
    low.resume();
  } else {
    initDynamic_();
  }
  return true;
}

int Controller::run(const RunOptions& opts, std::ostream& out, std::ostream& err) {
  // SIGSEGV & co. in a task become faults of that task (FB_INIT/FB_EXIT: of the run).
  installFaultSignals();
  setProgramMemory(image_, module_->image.size);
  const sema::Layout& layout = *model_.layout;
  bool warm = false;
  if (!opts.retainFile.empty()) {
    // Before anything runs: a file that is not ours is never replaced, and a save that
    // cannot succeed is found now rather than after the run.
    const RetainStart rs = restoreRetain(opts.retainFile, opts.cold, opts.retainReset, err);
    if (rs == RetainStart::Refused) return 2;
    std::string e;
    if (!retainWritable(opts.retainFile, e)) {
      err << "stc: error: retain file '" << opts.retainFile << "' cannot be saved: " << e << "; nothing ran\n";
      return 2;
    }
    warm = rs == RetainStart::Warm;
  }
  // Watches and traces are resolved before anything runs.
  std::vector<ValueRef> watches;
  for (const std::string& w : opts.watches) {
    ValueRef ref;
    std::string e;
    if (!resolvePath(module_->image, layout, w, ref, e)) {
      err << "stc: error: --watch " << w << ": " << e << "\n";
      return 2;
    }
    watches.push_back(ref);
  }
  std::vector<ValueRef> traced;
  std::unique_ptr<TraceWriter> trace;
  if (!opts.traces.empty()) {
    std::vector<TraceColumn> cols;
    // The units the libraries configure (axes): a traced variable inside one of their
    // variables (by memory, so `Axis1.x` and `GVL.Axis1.x` alike) takes the unit of the
    // innermost.
    struct UnitSpan {
      uint64_t begin, end;
      std::string unit;
    };
    std::vector<UnitSpan> units;
    for (const auto& s : sessions_)
      for (auto& [path, unit] : s->units()) {
        ValueRef r;
        std::string e;
        if (resolvePath(module_->image, layout, path, r, e) && r.type) units.push_back({r.offset, r.offset + layout.sizeOf(r.type), unit});
      }
    auto unitOf = [&units](const ValueRef& ref) {
      uint64_t best = UINT64_MAX;
      std::string unit;
      for (const UnitSpan& u : units)
        if (ref.offset >= u.begin && ref.offset < u.end && u.end - u.begin < best) best = u.end - u.begin, unit = u.unit;
      return unit;
    };
    for (const std::string& w : opts.traces) {
      ValueRef ref;
      std::string e;
      if (!resolvePath(module_->image, layout, w, ref, e)) {
        err << "stc: error: --trace " << w << ": " << e << "\n";
        return 2;
      }
      const sema::Type* t = ref.type->kind == sema::TypeKind::Subrange ? ref.type->element : ref.type;
      const sema::Type* u = t->underlying();
      TraceColumn c;
      c.name = w;
      if (t->kind == sema::TypeKind::Enum) c.kind = TraceColumn::Enum;   // by its value names, not its base integer
      else if (u->isBool()) c.kind = TraceColumn::Bool, c.bits = 1;
      else if (u->isReal()) c.kind = TraceColumn::Real, c.bits = u->bits();
      else if (u->isElementary() && !u->isString()) c.kind = TraceColumn::Int, c.bits = u->bits(), c.isSigned = u->isSignedInt() || u->isDuration();
      else c.kind = TraceColumn::Text;
      c.unit = unitOf(ref);
      cols.push_back(c);
      traced.push_back(ref);
    }
    std::string e;
    trace = TraceWriter::create(opts.traceOut.empty() ? "trace.csv" : opts.traceOut, cols, e, opts.traceCsv);
    if (!trace) {
      err << "stc: error: " << e << "\n";
      return 2;
    }
  }
  // FB_INIT of every instance, after the retained values are back.  A fault
  // there stops the run before the first cycle.
  FaultInfo initFault;
  if (!callOutsideTasks(fbInit_, !warm, initFault)) {
    reportFault(initFault, "runtime fault in FB_INIT, before the first cycle: ");
    return 3;
  }
  // Whether the natives must keep the {attribute 'mirrored'} structs current.
  bool mirroredRead = model_.readsMirrored || opts.observesMirrored;
  for (const ValueRef& r : watches) mirroredRead = mirroredRead || r.mirrored;
  for (const ValueRef& r : traced) mirroredRead = mirroredRead || r.mirrored;
  if (!opts.retainFile.empty())
    for (const RetainRegion& r : retainRegions()) mirroredRead = mirroredRead || sema::holdsMirrored(r.type);
  SchedulerOptions so;
  so.measure = opts.stats;
  so.realtime = opts.realtime;
  so.lowMemory = module_->lowMemory;
  sched_ = std::make_unique<Scheduler>(so);
  for (size_t i = 0; i < module_->tasks.size(); ++i) {
    const codegen::TaskPlan& plan = module_->tasks[i];
    TaskConfig tc;
    tc.name = plan.name;
    tc.kind = plan.kind == codegen::TaskPlan::Kind::Cyclic ? TaskKind::Cyclic
              : plan.kind == codegen::TaskPlan::Kind::Event ? TaskKind::Event : TaskKind::Freewheeling;
    tc.interval = plan.intervalNs;
    tc.priority = plan.priority;
    tc.mayBlock = plan.mayBlock;
    if (opts.watchdog) tc.watchdog = *opts.watchdog;
    if (opts.slice) tc.slice = *opts.slice;
    if (plan.singleOffset) {
      const uint8_t* flag = image_ + *plan.singleOffset;
      tc.eventInput = [flag] { return *flag != 0; };
    }
    TaskRuntime* rt = tasks_[i].get();
    if (rt->entries.size() == 1) tc.entry = rt->entries[0];
    else tc.entry = [rt] { for (auto* f : rt->entries) f(); };
    sched_->addTask(std::move(tc));
  }
  // The cycle: copy inputs in -> the task's programs -> native hooks -> copy outputs out.
  const codegen::ImageMap& im = module_->image;
  inputs_.resize(im.inputUsed);
  outputs_.resize(im.outputUsed);
  if (im.inputUsed || im.outputUsed || opts.beforeSlot)
    sched_->setSlotCallbacks(
        [this, &im, &opts](uint32_t) {
          if (opts.beforeSlot) opts.beforeSlot(sched_->now());
          if (!inputs_.empty()) std::memcpy(image_ + im.inputOffset, inputs_.data(), inputs_.size());
        },
        [this, &im](uint32_t) {
          if (!outputs_.empty()) std::memcpy(outputs_.data(), image_ + im.outputOffset, outputs_.size());
        });
  SessionScope scope(&sessionTable_);
  for (size_t i = 0; i < sessions_.size(); ++i) {
    NativeSession* s = sessions_[i].get();
    sched_->addCycleHook("native-" + std::to_string(i), [s](const HookCtx& c) { s->cycle(c); });
  }
  {
    StartCtx sc{*sched_, image_, module_->image.size, [this, &layout](const std::string& path, std::string& typeName) -> void* {
                  ValueRef ref;
                  std::string e;
                  if (!resolvePath(module_->image, layout, path, ref, e) || ref.bit >= 0) return nullptr;
                  typeName = ref.type->name;
                  return image_ + ref.offset;
                },
                [this, &layout, &im](const std::string& path, StartCtx::BoolTarget& out) -> bool {
                  ValueRef ref;
                  std::string e;
                  if (!resolvePath(module_->image, layout, path, ref, e) || !ref.type || ref.type->name != "BOOL") return false;
                  out.bit = ref.bit;
                  if (ref.offset >= im.inputOffset && ref.offset < im.inputOffset + inputs_.size())
                    out.byte = inputs_.data() + (ref.offset - im.inputOffset);
                  else
                    out.byte = image_ + ref.offset;
                  return true;
                },
                {}};
    sc.lookupVariable = [this](const std::string& path, StartCtx::Variable& out, std::string& e) -> bool {
      ValueRef ref;
      if (!resolvePath(module_->image, *model_.layout, path, ref, e)) return false;
      // Process inputs (%I) are copied into the image before each slot; the image is
      // where the program reads them, so reading there is right and a write would be lost.
      out.address = image_ + ref.offset;
      out.bit = ref.bit;
      out.typeName = ref.type ? ref.type->name : std::string();
      const codegen::ImageMap& m = module_->image;
      out.constant = ref.constant || (ref.offset >= m.inputOffset && ref.offset < m.inputOffset + m.inputSize);
      return true;
    };
    sc.mirroredRead = mirroredRead;
    for (const auto& s : sessions_) {
      std::string e;
      if (!s->start(sc, e)) {
        err << "stc: error: " << e << "\n";
        return 1;
      }
    }
  }
  if (trace) {
    TraceWriter* tw = trace.get();
    tickFn_ = [this, tw, &traced, &layout](Time now) {
      std::vector<TraceValue> values(traced.size());
      for (size_t k = 0; k < traced.size(); ++k) {
        const uint8_t* p = image_ + traced[k].offset;
        const sema::Type* u = traced[k].type->underlying();
        values[k].literal = valueText(traced[k]);
        if (u->isReal()) {
          if (u->kind == sema::TypeKind::Real) { float f; std::memcpy(&f, p, 4); values[k].real = f; }
          else std::memcpy(&values[k].real, p, 8);
        } else if (traced[k].bit >= 0) {
          values[k].bits = (*p >> traced[k].bit) & 1;
        } else if (u->isElementary() && !u->isString()) {
          unsigned n = std::max(1u, u->bits() / 8);
          uint64_t v = 0;
          std::memcpy(&v, p, n);
          values[k].bits = v;
        }
      }
      tw->sample(now, values);
    };
    sched_->setTickCallback(tickFn_);
  }
  if (opts.afterTick) {
    tickFn_ = [trace = std::move(tickFn_), &opts](Time now) {
      if (trace) trace(now);
      opts.afterTick(now);
    };
    sched_->setTickCallback(tickFn_);
  }
  bool retainFailed = false;
  auto retainSave = [this, &err, &retainFailed](const std::string& file) {
    std::string e;
    if (saveRetain(file, e)) return;
    // Reported once per run (a periodic save that keeps failing says so once); the run goes on
    // and ends with exit status 4.
    if (!retainFailed) err << "stc: error: cannot save retain file: " << e << "\n";
    retainFailed = true;
  };
  // Periods given on the command line fall on ticks of the tasks: a period shorter than or
  // between the tasks' ticks would make the controller tick at that period (a 1 ns period:
  // a billion ticks per second of simulated time) for nothing the program could see.
  const Time taskTick = sched_->baseTick();
  for (const auto& [option, every] : {std::pair{"--retain-every", opts.retainEvery}, std::pair{"--watch-every", opts.watchEvery}})
    if (every && *every > 0 && *every % taskTick != 0) {
      err << "stc: error: " << option << " " << formatIecTime(*every) << " is not a multiple of the tasks' tick " << formatIecTime(taskTick)
          << "\n";
      return 2;
    }
  if (!opts.retainFile.empty() && opts.retainEvery && *opts.retainEvery > 0) {
    // Periodic saves at tick boundaries: a killed process loses at most one period.
    Time every = *opts.retainEvery;
    auto next = std::make_shared<Time>(every);
    sched_->addTickPeriod(every);
    const std::string file = opts.retainFile;
    tickFn_ = [this, next, every, file, retainSave, tick = std::move(tickFn_)](Time now) {
      if (tick) tick(now);
      if (now + sched_->baseTick() >= *next) {
        retainSave(file);
        *next += every;
      }
    };
    sched_->setTickCallback(tickFn_);
  }
  if (opts.watchEvery && *opts.watchEvery > 0 && !watches.empty()) {
    // The watches on one line at every multiple of D (with --realtime: a live view).
    Time every = *opts.watchEvery;
    auto next = std::make_shared<Time>(every);
    tickFn_ = [this, next, every, &watches, &opts, &out, tick = std::move(tickFn_)](Time now) {
      if (tick) tick(now);
      const Time end = now + sched_->baseTick();   // the values after this tick are those of `end`
      if (end < *next) return;
      const Time at = end / every * every;
      out << "[" << formatIecTime(at) << "]";
      for (size_t k = 0; k < watches.size(); ++k) out << (k ? "; " : " ") << opts.watches[k] << " = " << valueText(watches[k]);
      out << "\n";
      out.flush();
      *next = at + every;
    };
    sched_->setTickCallback(tickFn_);
  }
  RunLimit limit;
  limit.cycles = opts.cycles;
  limit.until = opts.duration;
  if (!limit.cycles && !limit.until) limit.cycles = 1;
  gStopTarget = sched_.get();
  struct sigaction sa {};
  sa.sa_handler = onStopSignal;
  sigemptyset(&sa.sa_mask);
  struct sigaction oldInt {}, oldTerm {};
  sigaction(SIGINT, &sa, &oldInt);
  sigaction(SIGTERM, &sa, &oldTerm);
  sched_->run(limit);
  sigaction(SIGINT, &oldInt, nullptr);
  sigaction(SIGTERM, &oldTerm, nullptr);
  gStopTarget = nullptr;
  FaultInfo exitFault;
  bool exitFaulted = !callOutsideTasks(fbExit_, false, exitFault);
  if (!opts.retainFile.empty()) retainSave(opts.retainFile);
  if (trace) {
    // The run ends with its last tick (at the limit, or earlier when stopped).
    std::string e;
    Time end = sched_->now() + sched_->baseTick();
    if (limit.until) end = std::min(end, *limit.until);
    if (!trace->finish(end, e)) err << "stc: error: " << e << "\n";
  }
  for (size_t k = 0; k < watches.size(); ++k)
    out << opts.watches[k] << " = " << valueText(watches[k]) << "\n";
  out.flush();
  if (opts.stats) {
    for (size_t i = 0; i < sched_->taskCount(); ++i) {
      const TaskStats& s = sched_->stats()[i];
      err << "task '" << sched_->task(static_cast<uint32_t>(i)).name << "': " << s.slots << " slots, " << s.activations << " activations, "
          << s.overruns << " overruns, " << s.lostEvents << " lost events";
      if (s.slots)
        err << "; execution min " << s.execMinNs << " ns, avg " << s.execTotalNs / static_cast<int64_t>(s.slots) << " ns, max " << s.execMaxNs
            << " ns";
      err << "\n";
    }
  }
  reportFaults(err);
  if (exitFaulted) reportFault(exitFault, "runtime fault in FB_EXIT, after the last cycle: ");
  if (!sched_->faults().empty() || exitFaulted) return 3;
  return retainFailed ? 4 : 0;
}

std::string Controller::valueText(const ValueRef& r) const {
  if (r.bit >= 0) return (image_[r.offset] >> r.bit) & 1 ? "TRUE" : "FALSE";
  return formatValue(image_ + r.offset, r.type, *model_.layout);
}

std::vector<Controller::RetainRegion> Controller::retainRegions() const {
  std::vector<RetainRegion> out;
  const sema::Layout& layout = *model_.layout;
  std::function<void(const std::string&, uint64_t, const sema::Type*, int)> walk = [&](const std::string& path, uint64_t off,
                                                                                      const sema::Type* t, int depth) {
    if (depth > 16) return;
    const sema::Type* u = t->underlying();
    if (!(u->kind == sema::TypeKind::FunctionBlock || u->kind == sema::TypeKind::Program || u->kind == sema::TypeKind::Struct)) return;
    for (const sema::FieldLayout& f : layout.of(u).fields) {
      if (!f.type || f.indirect) continue;
      std::string p = path + "." + f.name;
      if (f.decl && (f.decl->isRetain || f.decl->isPersistent)) out.push_back({p, off + f.offset, f.type, f.decl->isPersistent});
      else walk(p, off + f.offset, f.type, depth + 1);
    }
  };
  for (const codegen::ImageRoot& r : module_->image.roots) {
    if (r.alias || r.constant) continue;
    if (r.retain || r.persistent) out.push_back({r.path, r.offset, r.type, r.persistent});
    else walk(r.path, r.offset, r.type, 0);
  }
  return out;
}

namespace {
struct OutsideRun {
  jmp_buf jb;
  FaultInfo info;
};
thread_local OutsideRun* tOutsideRun = nullptr;
void onOutsideFault(FaultInfo&& info) {
  tOutsideRun->info = std::move(info);
  _longjmp(tOutsideRun->jb, 1);
}
}  // namespace

// Runs generated code outside the tasks (FB_INIT, FB_EXIT); false with the
// fault if it faulted (the generated frames are abandoned, as in a task).
bool Controller::callOutsideTasks(void (*fn)(bool), bool arg, FaultInfo& fault) {
  SessionScope scope(&sessionTable_);
  __stc_budget = INT64_MAX / 2;
  OutsideRun run;
  OutsideRun* outer = tOutsideRun;
  tOutsideRun = &run;
  OutsideTaskFaultHandler prev = setOutsideTaskFaultHandler(onOutsideFault);
  bool ok = true;
  auto call = [&] {
    if (_setjmp(run.jb) == 0) {
      fn(arg);
    } else {
      ok = false;
      fault = std::move(run.info);
    }
  };
  if (module_->lowMemory) {
    // The 32-bit address model: locals of FB_INIT/FB_EXIT must lie below 4 GiB too.
    Fiber low(size_t{1} << 20, true);
    low.start(call);
    low.resume();
  } else {
    call();
  }
  setOutsideTaskFaultHandler(prev);
  tOutsideRun = outer;
  return ok;
}

void Controller::reportFaults(std::ostream&) {
  for (const TaskFault& f : sched_->faults())
    reportFault(f.info, "runtime fault in task '" + sched_->task(f.task).name + "', cycle " + std::to_string(f.cycle) + " (" +
                            formatIecTime(f.now) + "): ");
}

void Controller::reportFault(const FaultInfo& info, const std::string& prefix) {
  const codegen::Site* site = info.site < module_->sites.size() ? &module_->sites[info.site] : nullptr;
  std::string msg = prefix + info.message;
  if (site && !site->detail.empty() && info.code == "fault-index") msg += " of '" + site->detail + "'";
  if (site && site->detail == "MOD" && info.code == "fault-division-by-zero") msg = prefix + "MOD by zero";
  if (site && !site->detail.empty() && info.code == "fault-unbound-in-out") msg = prefix + "VAR_IN_OUT " + site->detail + " is not bound";
  SourceLoc at = site && site->loc.valid() ? site->loc : site ? site->range.begin : SourceLoc{};
  auto d = site && at.valid() ? diags_.error(at, msg, info.code.c_str()) : diags_.error(SourceLoc{}, msg, info.code.c_str());
  if (site && at.valid()) d.range(site->range);
  // The call chain: which caller passed the bad value.
  // A run of the same call site (a recursion through an interface) is one note.
  for (size_t k = 0; k < info.callers.size();) {
    uint32_t c = info.callers[k];
    size_t same = 1;
    while (k + same < info.callers.size() && info.callers[k + same] == c) ++same;
    k += same;
    const codegen::Site* cs = c < module_->sites.size() ? &module_->sites[c] : nullptr;
    if (!cs || !cs->range.valid()) continue;
    std::string text = (cs->detail.empty() ? std::string("called") : "'" + cs->detail + "' called") + " from '" + cs->pou + "' here";
    if (same > 1) text += " (" + std::to_string(same) + (same == 64 ? "+" : "") + " times in a row)";
    d.note(cs->range.begin, text, cs->range);
  }
}

}  // namespace stc::vm
