// Def structs as Python classes, their fields bound from app/fields.h: the names, defaults, help
// and ranges are the C++ ones, written once. Setting a field checks it as the command line does.
#pragma once

#include <pybind11/pybind11.h>

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "sim/fields.h"
#include "sim/names.h"
#include "sim/shell.h"

namespace pybinding {

namespace py = pybind11;

// Visitors of app/fields.h for one field, found by key: read it as a Python object (int, float or
// the enum's name), set it with the command line's range checks, or list the keys.
struct FieldReader {
    const std::string& key;
    py::object& out;
    void Integer(const char* k, const int& v, const char*, long long, long long) {
        if (key == k) out = py::int_(v);
    }
    void Number(const char* k, const double& v, const char*, double, double) {
        if (key == k) out = py::float_(v);
    }
    template <class E>
    void Enum(const char* k, const E& v, const char*) {
        if (key == k) out = py::str(sim::Name(v));
    }
};

struct FieldWriter {
    const std::string& key;
    const py::object& value;
    // A wrong type is a TypeError naming the field (pybind's own cast error names none).
    void Expect(bool ok, const char* k, const char* wanted) const {
        if (!ok) throw py::type_error(fmt::format("{}: expected {}, got {}", k, wanted, std::string(py::str(value.get_type().attr("__name__")))));
    }
    void Integer(const char* k, int& v, const char*, long long min, long long max) {
        if (key != k) return;
        Expect(py::hasattr(value, "__index__") && !py::isinstance<py::bool_>(value), k, "an int");  // NumPy's integers too
        const long long x = value.cast<long long>();
        if (x < min || x > max) throw py::value_error(fmt::format("{}: {} is out of range ({} to {})", k, x, min, max));
        v = static_cast<int>(x);
    }
    void Number(const char* k, double& v, const char*, double min, double max) {
        if (key != k) return;
        Expect(py::hasattr(value, "__float__") && !py::isinstance<py::bool_>(value) && !py::isinstance<py::str>(value), k, "a number");
        const double x = value.cast<double>();
        if (!(x >= min && x <= max)) throw py::value_error(fmt::format("{}: {} is out of range ({} to {})", k, x, min, max));
        v = x;
    }
    template <class E>
    void Enum(const char* k, E& v, const char*) {
        if (key != k) return;
        Expect(py::isinstance<py::str>(value), k, "a name (str)");
        const std::string text = value.cast<std::string>();
        const auto parsed = sim::FromName<E>(text);
        if (!parsed) throw py::value_error(fmt::format("{}: unknown value '{}' (choose {})", k, text, sim::Choices<E>()));
        v = *parsed;
    }
};

// The fields a def's Python class has: its fields, and for the load its kind, which the command line
// takes as --load and an experiment file as "kind" (every model's --load shares one option).
template <class Def, class Visitor>
void VisitBoundFields(Def& def, Visitor&& v) {
    if constexpr (std::is_same_v<std::remove_const_t<Def>, sim::LoadDef>)
        v.Enum("kind", def.kind, "inflate, gas, volume, force or blocked: what is held and what is stepped (docs/models/shell.md sections 6 and 12)");
    sim::VisitFields(def, v);
}

template <class Def>
py::object GetField(const Def& def, const std::string& key) {
    py::object out;
    VisitBoundFields(def, FieldReader{key, out});
    return out;
}

template <class Def>
void SetField(Def& def, const std::string& key, const py::object& value) {
    VisitBoundFields(def, FieldWriter{key, value});
}

template <class Def>
struct FieldLister {
    std::vector<std::string>& keys;
    py::class_<Def>& cls;
    void Add(const char* k, const char* help) {
        keys.push_back(k);
        const std::string key = k;
        cls.def_property(
            k, [key](const Def& d) { return GetField(d, key); }, [key](Def& d, const py::object& v) { SetField(d, key, v); }, help);
    }
    void Integer(const char* k, int&, const char* help, long long, long long) { Add(k, help); }
    void Number(const char* k, double&, const char* help, double, double) { Add(k, help); }
    template <class E>
    void Enum(const char* k, E&, const char* help) {
        Add(k, help);
    }
};

// A def struct as a Python class: a keyword constructor and one attribute per field, with its help;
// it pickles as its fields (process pools and Dask send it so).
template <class Def>
py::class_<Def> BindDef(py::module_& m, const char* name, const char* doc, Def defaults = Def{}) {
    py::class_<Def> cls(m, name, doc);
    std::vector<std::string> keys;
    Def probe = defaults;
    VisitBoundFields(probe, FieldLister<Def>{keys, cls});
    cls.def(py::init([defaults, keys](const py::kwargs& kwargs) {
        Def def = defaults;
        for (const auto& [key, value] : kwargs) {
            const std::string k = key.template cast<std::string>();
            if (std::find(keys.begin(), keys.end(), k) == keys.end()) {
                std::string valid;
                for (const auto& v : keys) valid += (valid.empty() ? "" : ", ") + v;
                throw py::value_error(fmt::format("unknown field '{}' (valid: {})", k, valid));
            }
            SetField(def, k, py::reinterpret_borrow<py::object>(value));
        }
        return def;
    }));
    const std::string className = name;
    cls.def("__repr__", [keys, className](const Def& d) {
        std::string text = className + "(";
        for (size_t k = 0; k < keys.size(); ++k) text += (k ? ", " : "") + keys[k] + "=" + std::string(py::repr(GetField(d, keys[k])));
        return text + ")";
    });
    cls.def(py::pickle(
        [keys](const Def& d) {
            py::dict state;
            for (const auto& k : keys) state[py::str(k)] = GetField(d, k);
            if constexpr (std::is_same_v<Def, sim::MaterialDef>) state["preset"] = sim::Name(d.preset);  // named after it, not a field
            return state;
        },
        [defaults](const py::dict& state) {
            Def def = defaults;
            for (const auto& [key, value] : state) {
                const std::string k = key.template cast<std::string>();
                if constexpr (std::is_same_v<Def, sim::MaterialDef>)
                    if (k == "preset") {
                        def.preset = sim::FromName<sim::MaterialPreset>(value.template cast<std::string>()).value_or(def.preset);
                        continue;
                    }
                SetField(def, k, py::reinterpret_borrow<py::object>(value));
            }
            return def;
        }));
    return cls;
}

}  // namespace pybinding
