#include "lua_controller/lua_script.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

namespace mrsim {

// Everything Lua's C callbacks reach. Lua (built as C) unwinds with
// longjmp, so no code below keeps an object with a destructor alive across
// a Lua call that may raise; C++ exceptions are thrown only outside
// lua_pcall.
struct LuaScript::Impl {
  LuaLimits limits;
  lua_State* L = nullptr;
  size_t used = 0;  // bytes the interpreter holds
  int64_t executed = 0;
  bool exceeded = false;
  bool memory_refused = false;
  int step_ref = LUA_NOREF;
  int step_line = 0;
  int gait_ref = LUA_NOREF;  // on_gait_command, when the script defines it
  std::vector<std::string> printed;
  ~Impl() {
    if (L != nullptr) lua_close(L);
  }
};

namespace {

// The count hook fires every kHookEvery instructions.
constexpr int kHookEvery = 1000;
constexpr int kMaxJoints = 4096;

LuaScript::Impl* ImplOf(lua_State* L) {
  return *static_cast<LuaScript::Impl**>(lua_getextraspace(L));
}

void* Allocate(void* ud, void* ptr, size_t osize, size_t nsize) {
  auto* impl = static_cast<LuaScript::Impl*>(ud);
  if (ptr == nullptr) osize = 0;  // then osize is a type tag, not a size
  if (nsize == 0) {
    std::free(ptr);
    impl->used -= osize;
    return nullptr;
  }
  if (nsize > osize && impl->used - osize + nsize > impl->limits.memory_bytes) {
    impl->memory_refused = true;
    return nullptr;  // Lua raises "not enough memory"
  }
  void* p = std::realloc(ptr, nsize);
  if (p != nullptr) impl->used = impl->used - osize + nsize;
  return p;
}

void CountHook(lua_State* L, lua_Debug*) {
  LuaScript::Impl* impl = ImplOf(L);
  impl->executed += impl->exceeded ? 1 : kHookEvery;
  if (impl->executed <= impl->limits.instructions) return;
  if (!impl->exceeded) {
    impl->exceeded = true;
    // From now on every instruction raises, so a pcall in the script
    // cannot swallow the stop and loop on.
    lua_sethook(L, CountHook, LUA_MASKCOUNT, 1);
  }
  lua_Debug ar;
  int line = 0;
  const char* source = "script";
  if (lua_getstack(L, 0, &ar) && lua_getinfo(L, "Sl", &ar)) {
    line = ar.currentline;
    source = ar.short_src;
  }
  lua_pushfstring(L,
                  "%s:%d: stopped after %I instructions (an endless loop?); "
                  "one call may run at most that many",
                  source, line,
                  static_cast<lua_Integer>(impl->limits.instructions));
  lua_error(L);
}

// print(...) into Impl::printed instead of stdout.
int Print(lua_State* L) {
  LuaScript::Impl* impl = ImplOf(L);
  const int n = lua_gettop(L);
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  for (int i = 1; i <= n; ++i) {
    if (i > 1) luaL_addchar(&b, '\t');
    luaL_tolstring(L, i, nullptr);
    luaL_addvalue(&b);
  }
  luaL_pushresult(&b);
  size_t len = 0;
  const char* s = lua_tolstring(L, -1, &len);
  if (impl->printed.size() < impl->limits.max_printed_lines) {
    try {
      impl->printed.emplace_back(s, std::min<size_t>(len, 4096));
    } catch (...) {
    }
  }
  return 0;
}

// Runs f(L) in protected mode; returns lua_pcall's status with the error
// message on the stack top when not LUA_OK.
template <class F>
int Protected(lua_State* L, F* f) {
  lua_pushcfunction(L, [](lua_State* L) -> int {
    F* fn = static_cast<F*>(lua_touserdata(L, 1));
    lua_remove(L, 1);
    return (*fn)(L);
  });
  lua_pushlightuserdata(L, f);
  return lua_pcall(L, 1, 0, 0);
}

// The trusted part: only safe libraries, deterministic math.random.
int OpenSandbox(lua_State* L) {
  const luaL_Reg libs[] = {{LUA_GNAME, luaopen_base},
                           {LUA_TABLIBNAME, luaopen_table},
                           {LUA_STRLIBNAME, luaopen_string},
                           {LUA_MATHLIBNAME, luaopen_math},
                           {LUA_UTF8LIBNAME, luaopen_utf8}};
  for (const luaL_Reg& lib : libs) {
    luaL_requiref(L, lib.name, lib.func, 1);
    lua_pop(L, 1);
  }
  // Files, code from strings or bytecode, and the collector's knobs.
  for (const char* name : {"dofile", "loadfile", "load", "collectgarbage"}) {
    lua_pushnil(L);
    lua_setglobal(L, name);
  }
  lua_pushcfunction(L, Print);
  lua_setglobal(L, "print");
  lua_getglobal(L, LUA_STRLIBNAME);
  lua_pushnil(L);
  lua_setfield(L, -2, "dump");
  lua_pop(L, 1);
  // Lua 5.4 seeds math.random from the clock: same script, same run.
  lua_getglobal(L, LUA_MATHLIBNAME);
  lua_getfield(L, -1, "randomseed");
  lua_pushinteger(L, 0);
  lua_call(L, 1, 0);
  lua_pop(L, 1);
  // package.loaded holds the libraries; nothing else is reachable.
  lua_pushnil(L);
  lua_setfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  return 0;
}

// The script line a Lua message points at: the first ":N:".
int LineOf(const std::string& message) {
  for (size_t i = 0; i < message.size(); ++i) {
    if (message[i] != ':') continue;
    size_t j = i + 1;
    int line = 0;
    while (j < message.size() && j - i <= 9 && message[j] >= '0' &&
           message[j] <= '9') {
      line = line * 10 + (message[j] - '0');
      ++j;
    }
    if (j > i + 1 && j < message.size() && message[j] == ':') return line;
  }
  return 0;
}

std::string TopMessage(lua_State* L) {
  const char* s = lua_tostring(L, -1);
  std::string text = s ? s : "(an error that is not a string)";
  lua_pop(L, 1);
  return text;
}

// The largest `params` array read: as many genes as a genome may have.
constexpr lua_Integer kMaxParameters = 1000;
constexpr size_t kMaxParameterName = 64;

struct ParamsRead {
  std::vector<LuaParameter>* out;
  std::string* error;  // set (and nothing thrown) for a bad declaration
  const char* name;    // the script's
};

// Reads the global `params` without running script code (raw access only):
// an array of {name=, min=, max=, start=}.
int ReadParams(lua_State* L, ParamsRead* read) {
  // Raw: a metatable the script put on _G runs no code here, outside the
  // instruction limit.
  lua_pushglobaltable(L);
  lua_pushliteral(L, "params");
  lua_rawget(L, -2);
  if (lua_isnil(L, -1)) return 0;
  char buffer[512];
  auto fail = [&](const char* text) { read->error->assign(text); };
  if (!lua_istable(L, -1)) {
    std::snprintf(buffer, sizeof buffer,
                  "%s: params must be an array of {name = ..., min = ..., "
                  "max = ..., start = ...}; it is a %s",
                  read->name, luaL_typename(L, -1));
    fail(buffer);
    return 0;
  }
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
  if (n > kMaxParameters) {
    std::snprintf(buffer, sizeof buffer,
                  "%s: params declares %lld parameters; at most %lld",
                  read->name, static_cast<long long>(n),
                  static_cast<long long>(kMaxParameters));
    fail(buffer);
    return 0;
  }
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    if (!lua_istable(L, -1)) {
      std::snprintf(buffer, sizeof buffer,
                    "%s: params[%lld] must be a table {name = ..., min = ..., "
                    "max = ..., start = ...}; it is a %s",
                    read->name, static_cast<long long>(i),
                    luaL_typename(L, -1));
      fail(buffer);
      return 0;
    }
    read->out->emplace_back();
    LuaParameter& p = read->out->back();
    lua_pushliteral(L, "name");
    lua_rawget(L, -2);
    size_t len = 0;
    const char* text =
        lua_type(L, -1) == LUA_TSTRING ? lua_tolstring(L, -1, &len) : nullptr;
    bool identifier = text != nullptr && len > 0 && len <= kMaxParameterName &&
                      !(text[0] >= '0' && text[0] <= '9');
    for (size_t k = 0; identifier && k < len; ++k) {
      const char c = text[k];
      identifier = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                   (c >= '0' && c <= '9') || c == '_';
    }
    if (!identifier) {
      std::snprintf(buffer, sizeof buffer,
                    "%s: params[%lld]: field 'name': expected a name of "
                    "letters, digits and _ (at most %zu), not starting with "
                    "a digit",
                    read->name, static_cast<long long>(i), kMaxParameterName);
      fail(buffer);
      return 0;
    }
    p.name.assign(text, len);
    lua_pop(L, 1);
    double* fields[] = {&p.min, &p.max, &p.start};
    const char* keys[] = {"min", "max", "start"};
    for (int f = 0; f < 3; ++f) {
      lua_pushstring(L, keys[f]);
      lua_rawget(L, -2);
      int is_number = 0;
      const lua_Number v =
          lua_type(L, -1) == LUA_TNUMBER ? lua_tonumberx(L, -1, &is_number) : 0;
      if (!is_number || !std::isfinite(v)) {
        std::snprintf(
            buffer, sizeof buffer,
            "%s: params[%lld] ('%s'): field '%s': expected a finite "
            "number, got %s",
            read->name, static_cast<long long>(i), p.name.c_str(), keys[f],
            is_number ? "a number that is not finite" : luaL_typename(L, -1));
        fail(buffer);
        return 0;
      }
      *fields[f] = v;
      lua_pop(L, 1);
    }
    const char* problem = nullptr;
    if (p.min > p.max) {
      problem = "field 'min' is above 'max'";
    } else if (p.start < p.min || p.start > p.max) {
      problem = "field 'start' is outside [min, max]";
    }
    for (size_t k = 0; problem == nullptr && k + 1 < read->out->size(); ++k) {
      if ((*read->out)[k].name == p.name) {
        problem = "field 'name' repeats an earlier parameter's";
      }
    }
    if (problem != nullptr) {
      std::snprintf(buffer, sizeof buffer,
                    "%s: params[%lld] ('%s'): %s (min %.17g, max %.17g, start "
                    "%.17g)",
                    read->name, static_cast<long long>(i), p.name.c_str(),
                    problem, p.min, p.max, p.start);
      fail(buffer);
      return 0;
    }
    lua_pop(L, 1);
  }
  return 0;
}

struct ParamsSet {
  const std::vector<LuaParameter>* parameters;
  const std::vector<double>* values;
};

// P = {name = value, ...}: a fresh table, so values do not leak between
// settings; set raw, so no metamethod of the script's runs here.
int SetParams(lua_State* L, ParamsSet* set) {
  lua_pushglobaltable(L);
  lua_pushliteral(L, "P");
  lua_createtable(L, 0, static_cast<int>(set->parameters->size()));
  for (size_t i = 0; i < set->parameters->size(); ++i) {
    lua_pushnumber(L, (*set->values)[i]);
    lua_setfield(L, -2, (*set->parameters)[i].name.c_str());
  }
  lua_rawset(L, -3);
  lua_pop(L, 1);
  return 0;
}

}  // namespace

LuaScript::LuaScript(const std::string& source, const std::string& name,
                     LuaLimits limits)
    : impl_(std::make_unique<Impl>()), name_(name) {
  impl_->limits = limits;
  if (source.size() > limits.max_source_bytes) {
    throw LuaScriptError(
        name + ": the script has " + std::to_string(source.size()) +
            " bytes; at most " + std::to_string(limits.max_source_bytes),
        0);
  }
  impl_->L = lua_newstate(Allocate, impl_.get());
  if (impl_->L == nullptr) {
    throw LuaScriptError(name + ": cannot start Lua (out of memory)", 0);
  }
  lua_State* L = impl_->L;
  *static_cast<Impl**>(lua_getextraspace(L)) = impl_.get();
  auto open = [](lua_State* L) { return OpenSandbox(L); };
  if (Protected(L, &open) != LUA_OK) {
    throw LuaScriptError(name + ": cannot start Lua: " + TopMessage(L), 0);
  }
  const std::string chunk = "=" + name;
  if (luaL_loadbufferx(L, source.data(), source.size(), chunk.c_str(), "t") !=
      LUA_OK) {
    const std::string message = TopMessage(L);
    throw LuaScriptError(message, LineOf(message));
  }
  impl_->executed = 0;
  impl_->exceeded = false;
  lua_sethook(L, CountHook, LUA_MASKCOUNT, kHookEvery);
  const int status = lua_pcall(L, 0, 0, 0);
  lua_sethook(L, nullptr, 0, 0);
  if (status != LUA_OK) {
    std::string message = TopMessage(L);
    if (impl_->memory_refused && status == LUA_ERRMEM) {
      message = name + ": ran out of memory (the limit is " +
                std::to_string(limits.memory_bytes >> 20) + " MiB)";
    }
    throw LuaScriptError(message, LineOf(message));
  }
  auto find_step = [](lua_State* L) {
    LuaScript::Impl* impl = ImplOf(L);
    lua_getglobal(L, "step");
    if (!lua_isfunction(L, -1)) {
      lua_pushnil(L);
      return 0;
    }
    lua_Debug ar;
    lua_pushvalue(L, -1);
    lua_getinfo(L, ">S", &ar);
    impl->step_line = ar.linedefined;
    impl->step_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    return 0;
  };
  if (Protected(L, &find_step) != LUA_OK) {
    const std::string message = TopMessage(L);
    throw LuaScriptError(message, LineOf(message));
  }
  auto find_gait = [](lua_State* L) {
    lua_getglobal(L, "on_gait_command");
    if (lua_isfunction(L, -1)) {
      ImplOf(L)->gait_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    } else {
      lua_pop(L, 1);
    }
    return 0;
  };
  if (Protected(L, &find_gait) != LUA_OK) {
    const std::string message = TopMessage(L);
    throw LuaScriptError(message, LineOf(message));
  }
  if (impl_->step_ref == LUA_NOREF || impl_->step_ref == LUA_REFNIL) {
    throw LuaScriptError(name +
                             ": no function step(t, state) (the controller "
                             "calls it each control step)",
                         0);
  }
  std::string params_error;
  ParamsRead read{&parameters_, &params_error, name.c_str()};
  auto read_params = [&read](lua_State* L) { return ReadParams(L, &read); };
  if (Protected(L, &read_params) != LUA_OK) {
    const std::string message = TopMessage(L);
    throw LuaScriptError(message, LineOf(message));
  }
  if (!params_error.empty()) throw LuaScriptError(params_error, 0);
  std::vector<double> starts;
  for (const LuaParameter& p : parameters_) starts.push_back(p.start);
  SetParameters(starts);
}

void LuaScript::SetParameters(const std::vector<double>& values) {
  if (values.size() != parameters_.size()) {
    throw std::invalid_argument(name_ + ": " + std::to_string(values.size()) +
                                " parameter values for " +
                                std::to_string(parameters_.size()) +
                                " declared parameters");
  }
  for (double v : values) {
    if (!std::isfinite(v)) {
      throw std::invalid_argument(name_ + ": a parameter value is not finite");
    }
  }
  if (parameters_.empty()) return;
  ParamsSet set{&parameters_, &values};
  auto fn = [&set](lua_State* L) { return SetParams(L, &set); };
  if (Protected(impl_->L, &fn) != LUA_OK) {
    const std::string message = TopMessage(impl_->L);
    throw LuaScriptError(message, LineOf(message));
  }
}

LuaScript::~LuaScript() = default;

std::optional<LuaScriptError> LuaScript::Check(const std::string& source,
                                               const std::string& name) {
  try {
    LuaScript script(source, name);
  } catch (const LuaScriptError& e) {
    return e;
  }
  return std::nullopt;
}

namespace {

struct StepCall {
  double t = 0;
  const LuaRobotState* state = nullptr;
  std::vector<double>* out = nullptr;
  const char* name = "";
};

void PushArray(lua_State* L, const std::vector<double>& values) {
  lua_createtable(L, static_cast<int>(values.size()), 0);
  for (size_t i = 0; i < values.size(); ++i) {
    lua_pushnumber(L, values[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void PushVector3(lua_State* L, const double (&v)[3]) {
  lua_createtable(L, 3, 0);
  for (int i = 0; i < 3; ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

// Sets `readings` (every reading, in order) and `by_kind` (kind name ->
// the readings of that kind, in order) on the table on top of the stack.
// One table per reading, shared by both.
void PushReadings(lua_State* L,
                  const std::vector<LuaRobotState::Reading>& readings) {
  lua_createtable(L, static_cast<int>(readings.size()), 0);
  lua_newtable(L);  // by_kind
  for (size_t r = 0; r < readings.size(); ++r) {
    const LuaRobotState::Reading& reading = readings[r];
    lua_createtable(L, 0, 3);
    lua_pushlstring(L, reading.kind.data(), reading.kind.size());
    lua_setfield(L, -2, "kind");
    lua_pushinteger(L, reading.face);
    lua_setfield(L, -2, "face");
    PushArray(L, reading.values);
    lua_setfield(L, -2, "values");
    lua_pushvalue(L, -1);
    lua_rawseti(L, -4, static_cast<lua_Integer>(r + 1));  // readings[r + 1]
    // by_kind[kind][#by_kind[kind] + 1] = reading
    lua_pushlstring(L, reading.kind.data(), reading.kind.size());
    if (lua_rawget(L, -3) != LUA_TTABLE) {
      lua_pop(L, 1);
      lua_newtable(L);
      lua_pushlstring(L, reading.kind.data(), reading.kind.size());
      lua_pushvalue(L, -2);
      lua_rawset(L, -5);
    }
    lua_insert(L, -2);  // ..., by_kind, list, reading
    lua_rawseti(L, -2, static_cast<lua_Integer>(lua_rawlen(L, -2) + 1));
    lua_pop(L, 1);  // the list
  }
  lua_setfield(L, -3, "by_kind");
  lua_setfield(L, -2, "readings");
}

int CallStep(lua_State* L, StepCall* call) {
  LuaScript::Impl* impl = ImplOf(L);
  const LuaRobotState& s = *call->state;
  const int n = static_cast<int>(s.angles.size());
  lua_rawgeti(L, LUA_REGISTRYINDEX, impl->step_ref);
  lua_pushnumber(L, call->t);
  lua_createtable(L, 0, 8);
  lua_pushnumber(L, call->t);
  lua_setfield(L, -2, "t");
  lua_pushinteger(L, n);
  lua_setfield(L, -2, "n");
  PushArray(L, s.angles);
  lua_setfield(L, -2, "angles");
  PushArray(L, s.speeds);
  lua_setfield(L, -2, "speeds");
  PushArray(L, s.torques);
  lua_setfield(L, -2, "torques");
  PushVector3(L, s.com);
  lua_setfield(L, -2, "com");
  PushVector3(L, s.com_velocity);
  lua_setfield(L, -2, "com_velocity");
  lua_createtable(L, 4, 0);
  for (int i = 0; i < 4; ++i) {
    lua_pushnumber(L, s.orientation[i]);
    lua_rawseti(L, -2, i + 1);
  }
  lua_setfield(L, -2, "orientation");
  lua_pushnumber(L, s.heading);
  lua_setfield(L, -2, "heading");
  lua_createtable(L, static_cast<int>(s.sensors.size()), 0);
  for (size_t i = 0; i < s.sensors.size(); ++i) {
    lua_createtable(L, 0, 4);
    if (s.sensors[i].has_force) {
      lua_pushnumber(L, s.sensors[i].force);
      lua_setfield(L, -2, "force");
    }
    PushArray(L, s.sensors[i].distances);
    lua_setfield(L, -2, "distances");
    PushReadings(L, s.sensors[i].readings);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "sensors");
  lua_createtable(L, static_cast<int>(s.cameras.size()), 0);
  for (size_t i = 0; i < s.cameras.size(); ++i) {
    const LuaRobotState::Camera& c = s.cameras[i];
    lua_createtable(L, 0, 7);
    lua_pushinteger(L, c.width);
    lua_setfield(L, -2, "width");
    lua_pushinteger(L, c.height);
    lua_setfield(L, -2, "height");
    lua_pushinteger(L, c.seq);
    lua_setfield(L, -2, "seq");
    lua_pushnumber(L, c.sim_time);
    lua_setfield(L, -2, "sim_time");
    lua_pushinteger(L, c.grey_width);
    lua_setfield(L, -2, "grey_width");
    lua_pushinteger(L, c.grey_height);
    lua_setfield(L, -2, "grey_height");
    PushArray(L, c.grey);
    lua_setfield(L, -2, "grey");
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "cameras");
  if (!s.axes.empty()) {
    lua_createtable(L, static_cast<int>(s.axes.size()), 0);
    for (size_t i = 0; i < s.axes.size(); ++i) {
      lua_pushstring(L, s.axes[i].c_str());
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "axes");
  }
  lua_call(L, 2, 1);
  const char* name = call->name;
  if (!lua_istable(L, -1)) {
    return luaL_error(L,
                      "%s:%d: step must return a table of %d numbers (one "
                      "target angle per joint, rad); it returned a %s",
                      name, impl->step_line, n, luaL_typename(L, -1));
  }
  const lua_Integer len = luaL_len(L, -1);
  if (len != n) {
    return luaL_error(L,
                      "%s:%d: step must return %d numbers (one target angle "
                      "per joint, rad); it returned %I",
                      name, impl->step_line, n, len);
  }
  for (int i = 1; i <= n; ++i) {
    lua_rawgeti(L, -1, i);
    int is_number = 0;
    const lua_Number v = lua_tonumberx(L, -1, &is_number);
    if (!is_number || !std::isfinite(v)) {
      return luaL_error(L,
                        "%s:%d: step's result [%d] is %s, expected a finite "
                        "angle (rad)",
                        name, impl->step_line, i,
                        is_number ? "not finite" : luaL_typename(L, -1));
    }
    (*call->out)[static_cast<size_t>(i - 1)] = v;
    lua_pop(L, 1);
  }
  return 0;
}

}  // namespace

std::vector<double> LuaScript::Step(double t, const LuaRobotState& state) {
  const size_t n = state.angles.size();
  if (n > static_cast<size_t>(kMaxJoints) || state.speeds.size() != n ||
      state.torques.size() != n ||
      (!state.axes.empty() && state.axes.size() != n)) {
    throw std::invalid_argument("LuaScript::Step: inconsistent state");
  }
  std::vector<double> out(n, 0.0);
  StepCall call{t, &state, &out, name_.c_str()};
  lua_State* L = impl_->L;
  impl_->executed = 0;
  impl_->exceeded = false;
  impl_->memory_refused = false;
  lua_sethook(L, CountHook, LUA_MASKCOUNT, kHookEvery);
  auto fn = [&call](lua_State* L) { return CallStep(L, &call); };
  const int status = Protected(L, &fn);
  lua_sethook(L, nullptr, 0, 0);
  if (status != LUA_OK || impl_->exceeded) {
    std::string message =
        status != LUA_OK ? TopMessage(L) : name_ + ": stopped (instructions)";
    if (impl_->memory_refused && status == LUA_ERRMEM) {
      message = name_ + ": step ran out of memory (the limit is " +
                std::to_string(impl_->limits.memory_bytes >> 20) + " MiB)";
    }
    throw LuaScriptError(message, LineOf(message));
  }
  return out;
}

namespace {

struct GaitCall {
  const LuaGaitCommand* command;
  std::string* refusal;
};

int CallGait(lua_State* L, GaitCall* call) {
  const LuaGaitCommand& c = *call->command;
  lua_rawgeti(L, LUA_REGISTRYINDEX, ImplOf(L)->gait_ref);
  lua_createtable(L, 0, 7);
  lua_pushlstring(L, c.sender.data(), c.sender.size());
  lua_setfield(L, -2, "sender");
  if (!c.motion.empty()) {
    lua_pushlstring(L, c.motion.data(), c.motion.size());
    lua_setfield(L, -2, "motion");
    lua_pushnumber(L, c.strength);
    lua_setfield(L, -2, "strength");
  }
  if (!c.gait.empty()) {
    lua_pushlstring(L, c.gait.data(), c.gait.size());
    lua_setfield(L, -2, "gait");
  }
  if (!c.parameters.empty()) {
    PushArray(L, c.parameters);
    lua_setfield(L, -2, "parameters");
  }
  if (c.has_direction) {
    lua_pushnumber(L, c.forward);
    lua_setfield(L, -2, "forward");
    lua_pushnumber(L, c.turn);
    lua_setfield(L, -2, "turn");
  }
  lua_call(L, 1, 2);
  // nil or true: taken; false (and a reason): refused.
  if (lua_isboolean(L, -2) && !lua_toboolean(L, -2)) {
    const char* why = lua_isstring(L, -1) ? lua_tostring(L, -1) : nullptr;
    *call->refusal = why != nullptr && *why != '\0'
                         ? why
                         : "the script's on_gait_command refused it";
  }
  lua_pop(L, 2);
  return 0;
}

}  // namespace

bool LuaScript::takes_gait_commands() const {
  return impl_->gait_ref != LUA_NOREF && impl_->gait_ref != LUA_REFNIL;
}

std::string LuaScript::OnGaitCommand(const LuaGaitCommand& command) {
  if (!takes_gait_commands()) {
    throw std::logic_error("LuaScript: the script has no on_gait_command");
  }
  std::string refusal;
  GaitCall call{&command, &refusal};
  lua_State* L = impl_->L;
  impl_->executed = 0;
  impl_->exceeded = false;
  impl_->memory_refused = false;
  lua_sethook(L, CountHook, LUA_MASKCOUNT, kHookEvery);
  auto fn = [&call](lua_State* L) { return CallGait(L, &call); };
  const int status = Protected(L, &fn);
  lua_sethook(L, nullptr, 0, 0);
  if (status != LUA_OK || impl_->exceeded) {
    std::string message =
        status != LUA_OK ? TopMessage(L) : name_ + ": stopped (instructions)";
    if (impl_->memory_refused && status == LUA_ERRMEM) {
      message = name_ + ": on_gait_command ran out of memory (the limit is " +
                std::to_string(impl_->limits.memory_bytes >> 20) + " MiB)";
    }
    throw LuaScriptError(message, LineOf(message));
  }
  return refusal;
}

std::vector<std::string> LuaScript::TakePrinted() {
  std::vector<std::string> out;
  out.swap(impl_->printed);
  return out;
}

}  // namespace mrsim
