// The field conversions the generated message bindings are made of
// (python_messages.h, from lcmtypes/py_message_gen.py): one LCM value to
// Python (ToPy) and back (FieldReader::Take), whatever its type (number,
// boolean, string, struct, fixed or variable array of them). Strings from
// the network need not be UTF-8: bad bytes become U+FFFD instead of an
// exception. Values from Python are checked against the field's type, size
// and `// max:` limit; errors name the field.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mrsim::python::messages {

// How an LCM value reads in Python beyond its C++ type: LCM's boolean and
// byte are int8_t/uint8_t in C++, bool and bytes in Python.
enum class Kind { kPlain, kBool, kBytes };

// At most `string_max` bytes in each string, `count_max` elements in a
// variable array (-1: no limit).
struct Limits {
  int64_t string_max = -1;
  int64_t count_max = -1;
};

// One field of MessageTypes(): {name, type, dims, max}.
inline pybind11::dict Field(const char* name, const char* type,
                            pybind11::tuple dims, pybind11::object max) {
  pybind11::dict f;
  f["name"] = name;
  f["type"] = type;
  f["dims"] = std::move(dims);
  f["max"] = std::move(max);
  return f;
}

inline pybind11::object ToPyString(const std::string& s) {
  PyObject* str = PyUnicode_DecodeUTF8(
      s.data(), static_cast<Py_ssize_t>(s.size()), "replace");
  if (str == nullptr) throw pybind11::error_already_set();
  return pybind11::reinterpret_steal<pybind11::object>(str);
}

template <Kind K, class T>
pybind11::object ToPy(const T& value);
template <Kind K, class T, size_t N>
pybind11::object ToPy(const T (&items)[N]);
template <Kind K, class T>
pybind11::object ToPy(const std::vector<T>& items);

template <Kind K, class T>
pybind11::object ToPySequence(const T* items, size_t n) {
  if constexpr (std::is_arithmetic_v<T>) {
    if constexpr (K == Kind::kBytes) {
      return pybind11::bytes(reinterpret_cast<const char*>(items), n);
    } else if constexpr (K == Kind::kBool) {
      pybind11::array_t<bool> a(static_cast<pybind11::ssize_t>(n));
      bool* d = a.mutable_data();
      for (size_t i = 0; i < n; ++i) d[i] = items[i] != 0;
      return std::move(a);
    } else {
      return pybind11::array_t<T>(static_cast<pybind11::ssize_t>(n), items);
    }
  } else {
    pybind11::list list(n);
    for (size_t i = 0; i < n; ++i) list[i] = ToPy<K>(items[i]);
    return std::move(list);
  }
}

template <Kind K, class T, size_t N>
pybind11::object ToPy(const T (&items)[N]) {
  return ToPySequence<K>(items, N);
}

template <Kind K, class T>
pybind11::object ToPy(const std::vector<T>& items) {
  return ToPySequence<K>(items.data(), items.size());
}

template <Kind K, class T>
pybind11::object ToPy(const T& value) {
  if constexpr (std::is_same_v<T, std::string>) {
    return ToPyString(value);
  } else if constexpr (std::is_arithmetic_v<T>) {
    if constexpr (K == Kind::kBool) return pybind11::bool_(value != 0);
    return pybind11::cast(value);
  } else {
    return MessageToDict(value);  // a nested struct, found by ADL
  }
}

// Reads the fields of one struct from a dict (or any mapping), refusing
// names the struct does not have. `where` names the struct in errors
// ("sim_status_t", "robot_state_t.joints[2].world").
class FieldReader {
 public:
  FieldReader(pybind11::handle obj, std::string where,
              std::initializer_list<const char*> names)
      : where_(std::move(where)) {
    if (!PyMapping_Check(obj.ptr()) ||
        pybind11::isinstance<pybind11::str>(obj)) {
      throw pybind11::type_error(where_ + ": expected a dict of fields, got " +
                                 TypeOf(obj));
    }
    fields_ =
        pybind11::dict(pybind11::reinterpret_borrow<pybind11::object>(obj));
    for (auto item : fields_) {
      const std::string key = pybind11::str(item.first);
      bool known = false;
      for (const char* n : names) known = known || key == n;
      if (!known) {
        std::string list;
        for (const char* n : names)
          list += (list.empty() ? "" : ", ") + std::string(n);
        throw pybind11::value_error(where_ + ": no field '" + key +
                                    "' (fields: " + list + ")");
      }
    }
  }

  // The field `name` into *out; left as it is when absent or None.
  template <Kind K, class T>
  void Take(const char* name, T* out, const Limits& limits) {
    if (!fields_.contains(name)) return;
    pybind11::object value = fields_[name];
    if (value.is_none()) return;
    Read<K>(value, out, limits, where_ + "." + name);
  }

  // A length member: the size of the arrays it sizes, which must agree
  // with each other and with the value given for it, if any.
  template <class T>
  void Length(const char* name, T* out,
              std::initializer_list<std::pair<const char*, size_t>> arrays) {
    const auto& first = *arrays.begin();
    for (const auto& a : arrays) {
      if (a.second != first.second) {
        throw pybind11::value_error(
            where_ + "." + a.first + ": " + std::to_string(a.second) +
            " elements, but " + first.first + " has " +
            std::to_string(first.second) + " (both sized by " + name + ")");
      }
    }
    if (fields_.contains(name) && !fields_[name].is_none()) {
      T given{};
      Read<Kind::kPlain>(fields_[name], &given, Limits{}, where_ + "." + name);
      if (static_cast<size_t>(given) != first.second) {
        throw pybind11::value_error(
            where_ + "." + name + ": " + std::to_string(given) + ", but " +
            first.first + " has " + std::to_string(first.second) + " elements");
      }
    }
    *out = static_cast<T>(first.second);
  }

 private:
  static std::string TypeOf(pybind11::handle h) {
    return pybind11::str(pybind11::type::handle_of(h).attr("__name__"));
  }

  template <Kind K, class T>
  static void Read(pybind11::handle h, T* out, const Limits& limits,
                   const std::string& where) {
    if constexpr (std::is_same_v<T, std::string>) {
      if (pybind11::isinstance<pybind11::bytes>(h)) {
        *out = h.cast<std::string>();
      } else if (pybind11::isinstance<pybind11::str>(h)) {
        *out = h.cast<std::string>();
      } else {
        throw pybind11::type_error(where + ": expected str, got " + TypeOf(h));
      }
      if (limits.string_max >= 0 &&
          out->size() > static_cast<size_t>(limits.string_max)) {
        throw pybind11::value_error(
            where + ": " + std::to_string(out->size()) + " bytes, at most " +
            std::to_string(limits.string_max) + " (its // max:)");
      }
    } else if constexpr (std::is_arithmetic_v<T>) {
      if constexpr (K == Kind::kBool) {
        const int truth = PyObject_IsTrue(h.ptr());
        if (truth < 0) throw pybind11::error_already_set();
        *out = static_cast<T>(truth);
      } else {
        try {
          *out = h.cast<T>();
        } catch (const pybind11::cast_error&) {
          throw pybind11::type_error(
              where + ": expected " +
              (std::is_floating_point_v<T>
                   ? std::string("a number")
                   : "an integer of " + std::to_string(sizeof(T)) +
                         " byte(s)") +
              ", got " + pybind11::repr(h).cast<std::string>());
        }
      }
    } else if constexpr (std::is_array_v<T>) {
      constexpr size_t kN = std::extent_v<T>;
      pybind11::sequence items = Items(h, where);
      if (items.size() != kN) {
        throw pybind11::value_error(where + ": expected " + std::to_string(kN) +
                                    " values, got " +
                                    std::to_string(items.size()));
      }
      for (size_t i = 0; i < kN; ++i) {
        Read<K>(items[i], &(*out)[i], limits, Index(where, i));
      }
    } else if constexpr (IsVector<T>::value) {
      pybind11::sequence items = Items(h, where);
      if (limits.count_max >= 0 &&
          items.size() > static_cast<size_t>(limits.count_max)) {
        throw pybind11::value_error(
            where + ": " + std::to_string(items.size()) +
            " elements, at most " + std::to_string(limits.count_max) +
            " (its // max:)");
      }
      out->assign(items.size(), typename T::value_type{});
      for (size_t i = 0; i < items.size(); ++i) {
        Read<K>(items[i], &(*out)[i], limits, Index(where, i));
      }
    } else {
      MessageFromDict(h, out, where);  // a nested struct, found by ADL
    }
  }

  template <class T>
  struct IsVector : std::false_type {};
  template <class T, class A>
  struct IsVector<std::vector<T, A>> : std::true_type {};

  static pybind11::sequence Items(pybind11::handle h,
                                  const std::string& where) {
    if (!PySequence_Check(h.ptr()) || pybind11::isinstance<pybind11::str>(h)) {
      throw pybind11::type_error(where + ": expected a sequence, got " +
                                 TypeOf(h));
    }
    return pybind11::reinterpret_borrow<pybind11::sequence>(h);
  }

  static std::string Index(const std::string& where, size_t i) {
    return where + "[" + std::to_string(i) + "]";
  }

  std::string where_;
  pybind11::dict fields_;
};

}  // namespace mrsim::python::messages
