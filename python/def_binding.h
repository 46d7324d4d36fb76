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
    void Bands(const char* k, const std::vector<sim::FibreBand>& v, const char*) {
        if (key != k) return;
        py::list bands;
        for (const auto& b : v) bands.append(py::dict(py::arg("from") = b.from, py::arg("to") = b.to, py::arg("angle_deg") = b.angleDeg));
        out = bands;
    }
    void Angles(const char* k, const std::vector<double>& v, const char*) {
        if (key == k) out = py::cast(v);
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
    // Lists as the experiment file's keys take them: bands as [{"from": 0, "to": 0.5, "angle_deg": 30}, ...]
    // (or (from, to, angle_deg) tuples), sector angles as 1, 2 or 4 numbers; whether the bands cover the
    // length is the def's check (ShellDefError), as for a file.
    static double ListNumber(const py::handle& x, const std::string& where, double min, double max) {
        if (!py::hasattr(x, "__float__") || py::isinstance<py::bool_>(x) || py::isinstance<py::str>(x))
            throw py::type_error(fmt::format("{}: expected a number, got {}", where, std::string(py::str(x.get_type().attr("__name__")))));
        const double value = x.cast<double>();
        if (!(value >= min && value <= max)) throw py::value_error(fmt::format("{}: {} is out of range ({} to {})", where, value, min, max));
        return value;
    }
    py::list Sequence(const char* k, size_t most) const {
        Expect(py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value), k, "a list");
        py::list items(value);
        if (items.size() > most) throw py::value_error(fmt::format("{}: {} entries, at most {}", k, items.size(), most));
        return items;
    }
    void Bands(const char* k, std::vector<sim::FibreBand>& v, const char*) {
        if (key != k) return;
        std::vector<sim::FibreBand> bands;
        const py::list items = Sequence(k, 1000);
        for (size_t n = 0; n < items.size(); ++n) {
            const std::string where = fmt::format("{}[{}]", k, n);
            py::handle item = items[n];
            std::vector<py::object> numbers;
            if (py::isinstance<py::dict>(item)) {
                const py::dict band = py::reinterpret_borrow<py::dict>(item);
                for (const auto& [name, x] : band) {
                    const std::string field = py::str(name);
                    if (field != "from" && field != "to" && field != "angle_deg")
                        throw py::value_error(fmt::format("{}: unknown key '{}' (valid: from, to, angle_deg)", where, field));
                }
                for (const char* field : {"from", "to", "angle_deg"}) {
                    if (!band.contains(field)) throw py::value_error(fmt::format("{}: missing '{}' (a band is {{'from', 'to', 'angle_deg'}})", where, field));
                    numbers.push_back(band[field]);
                }
            } else if ((py::isinstance<py::tuple>(item) || py::isinstance<py::list>(item)) && py::len(item) == 3) {
                for (const auto& x : item) numbers.push_back(py::reinterpret_borrow<py::object>(x));
            } else {
                throw py::type_error(where + ": expected a band, {'from': 0, 'to': 0.5, 'angle_deg': 30} or (from, to, angle_deg)");
            }
            bands.push_back({ListNumber(numbers[0], where + ".from", 0, 1), ListNumber(numbers[1], where + ".to", 0, 1),
                             ListNumber(numbers[2], where + ".angle_deg", -90, 90)});
        }
        v = std::move(bands);
    }
    void Angles(const char* k, std::vector<double>& v, const char*) {
        if (key != k) return;
        std::vector<double> angles;
        const py::list items = Sequence(k, 4);
        for (size_t n = 0; n < items.size(); ++n) angles.push_back(ListNumber(items[n], fmt::format("{}[{}]", k, n), -90, 90));
        v = std::move(angles);
    }
};

// The fields a def's Python class has: its fields, and for the load its kind, which the command line
// takes as --load and an experiment file as "kind" (every model's --load shares one option).
template <class Def, class Visitor>
void VisitBoundFields(Def& def, Visitor&& v) {
    if constexpr (std::is_same_v<std::remove_const_t<Def>, sim::LoadDef>)
        v.Enum("kind", def.kind, "inflate, gas, volume, force or blocked: what is held and what is stepped (docs/models/shell.md sections 6 and 12)");
    sim::VisitFields(def, v);
    if constexpr (std::is_same_v<std::remove_const_t<Def>, sim::FibreDef>) {
        v.Bands("fibre_bands", def.bands, "angles by band along the length: [{'from': 0, 'to': 0.5, 'angle_deg': 30}, ...] covering 0 to 1 "
                                          "in order ([]: fibre_angle_deg everywhere); as an experiment file's \"fibre_bands\"");
        v.Angles("fibre_sectors_deg", def.sectorAnglesDeg, "or angles by angular sector, 1, 2 or 4 of them, as the thesis's B-spline sectors; "
                                                           "as an experiment file's \"fibre_sectors_deg\"");
    }
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
    void Bands(const char* k, std::vector<sim::FibreBand>&, const char* help) { Add(k, help); }
    void Angles(const char* k, std::vector<double>&, const char* help) { Add(k, help); }
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
