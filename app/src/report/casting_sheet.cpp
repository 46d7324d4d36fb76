#include "report/casting_sheet.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

namespace app {

namespace {

double Number(const Json& j, const char* key) { return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN; }

// What each printed file is best printed in: the core as its kind needs, the rest in a rigid plastic.
std::string PrintMaterial(const std::string& file, const std::string& core) {
    if (file.rfind("mold_core", 0) == 0)
        return core == "lost" ? "PVA or BVOH (dissolves in water), or a casting wax" : "PLA or PETG, smooth (sand the layer lines on the cavity's faces)";
    if (file.rfind("fitting", 0) == 0) return "PETG or a tough resin (it carries the clamp)";
    return "PLA or PETG";
}

}  // namespace

std::string CastingSheet(const Json& m) {
    const Json& silicone = m["silicone"];
    const Json& pour = m["pour"];
    const Json& core = m["core"];
    const std::string coreKind = core["kind"].get<std::string>();
    std::string out = fmt::format("# Casting the actuator\n\nA wall of {:g} mm ({} on the design's surface), {:.1f} g of {} in the part. Lengths in mm.\n\n",
                                  m["part"]["wall_mm"].get<double>(), m["part"]["wall"].get<std::string>(), Number(silicone, "mass_g"),
                                  silicone["material"].get<std::string>());
    out += "## 1. Print\n\n| file | orientation | size on the bed (mm) | fits the printer | print in |\n|---|---|---|---|---|\n";
    for (const Json& f : m["files"]) {
        const std::string file = f["file"].get<std::string>();
        if (!f["print"].contains("size_mm")) continue;  // the actuator itself is cast
        const Json& size = f["print"]["size_mm"];
        out += fmt::format("| {} | {} | {:.0f} x {:.0f} x {:.0f} | {} | {} |\n", file, f["print"]["orientation"].get<std::string>(), size[0].get<double>(),
                           size[1].get<double>(), size[2].get<double>(), f["print"]["fits_printer"].get<bool>() ? "yes" : "**no**",
                           PrintMaterial(file, coreKind));
    }
    out += fmt::format("\nThe printer's build volume: {:g} x {:g} x {:g}.\n\n", m["printer_mm"][0].get<double>(), m["printer_mm"][1].get<double>(),
                       m["printer_mm"][2].get<double>());
    out += "## 2. Prepare and assemble\n\n"
           "1. Clear the sprue (shell A's bottom end wall), the four vents (the top end wall) and the core's channels of stringing.\n"
           "2. Coat the cavity faces and the core with a release agent for platinum silicone. Keep sulphur clays, latex and uncured "
           "resin prints away from the silicone: they inhibit its cure.\n"
           "3. Lay the core in shell B, its handles in the end walls' channels; close shell A over it, pins into holes, and clamp or "
           "tape the halves together along their length.\n";
    out += fmt::format("4. Stand the mold {}.\n\n", pour["orientation"].get<std::string>());
    const Json& grams = pour["to_mix_g"];
    const Json& ml = pour["silicone_ml"];
    out += fmt::format("## 3. Mix\n\n{:.1f} g of part A and {:.1f} g of part B ({} by weight): {:.1f} ml, for the cavity's {:.1f} ml, the sprue's and "
                       "vents' {:.1f} ml and a margin of {} for what stays in the cup and the tube. Mix, scrape the sides, and degas.\n\n",
                       Number(grams, "part_a"), Number(grams, "part_b"), pour["mix_ratio_a_to_b_by_weight"].get<std::string>(), Number(ml, "to_mix"),
                       Number(ml, "cavity"), Number(ml, "sprue_and_vents"), pour["margin"].get<std::string>());
    out += "## 4. Pour from below\n\n";
    const Json& handling = pour["handling"];
    const Json& sprue = pour["sprue"];
    out += fmt::format("The sprue is a slot {:.1f} mm across the wall over {:.0f} deg of arc; it carries {:.0f} % of the fill's resistance. ",
                       Number(sprue, "across_mm"), Number(sprue, "arc_deg"), 100 * Number(sprue, "share_of_fill_resistance"));
    if (pour.contains("fill")) {
        const Json& fill = pour["fill"];
        const std::string method = fill["method"].get<std::string>();
        out += fmt::format("At {:g} cps ({}) the cavity fills in about {:.1f} min from a funnel whose level is {:g} mm above the block's top, "
                           "through a tube into the sprue, or in {:.1f} min from a syringe pushed at {:g} kPa. ",
                           Number(handling, "mixed_viscosity_cps"), handling["source"].get<std::string>(), Number(fill, "gravity_min"),
                           Number(fill, "funnel_above_top_mm"), Number(fill, "syringe_min"), Number(fill, "syringe_kpa"));
        if (method == "gravity") out += fmt::format("The pot life is {:g} min: pour by gravity.", Number(handling, "pot_life_min"));
        else if (method == "syringe") out += fmt::format("The pot life is {:g} min: gravity is too slow; use the syringe.", Number(handling, "pot_life_min"));
        else if (method == "too slow")
            out += fmt::format("**The pot life is {:g} min: even the syringe needs more than half of it.** Use a slower version of the silicone, a "
                               "thinner, or a wider wall.",
                               Number(handling, "pot_life_min"));
        out += "\n\n";
    } else {
        out += handling["source"].get<std::string>() + ".\n\n";
    }
    out += "Fill until silicone rises out of all four vents, then close the sprue (tape or a plug) and leave the mold upright.\n\n";
    out += "## 5. Cure and demould\n\n";
    if (handling.contains("cure_h") && handling["cure_h"].is_number())
        out += fmt::format("Cure {:g} h at room temperature (the bulletin's time). ", Number(handling, "cure_h"));
    std::string how = core["how"].get<std::string>();
    if (!how.empty()) how[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(how[0])));
    out += "Open the shells along the split plane. " + how;
    out += ". Trim the sprue's and the vents' tabs from the ends.\n";
    if (m.contains("fibres")) {
        const Json& f = m["fibres"];
        out += fmt::format("\n## {}. Fibres\n\n{} ({} N/mm per family): {}. Winding order: {}.\n\n", m.contains("fittings") ? 7 : 6,
                           f["layout"].get<std::string>(), Number(f, "stiffness_n_per_mm"), f["how"].get<std::string>(), f["order"].get<std::string>());
        out += "| family | hand | band (mm from the bottom) | angle to the meridian (deg) | turns | pitch (mm per turn) |\n|---|---|---|---|---|---|\n";
        for (const Json& family : f["families"])
            for (const Json& b : family["bands"]) {
                const double angle = Number(b, "angle_deg"), pitch = Number(b, "pitch_mm");
                out += fmt::format("| {} | {} | {:.1f} to {:.1f} | {} | {:.2f} | {} |\n", family["family"].get<std::string>(),
                                   family["hand"].get<std::string>(), Number(b, "from_mm"), Number(b, "to_mm"),
                                   std::isfinite(angle) ? fmt::format("{:.1f}", angle) : "by sector", Number(b, "turns"),
                                   std::isfinite(pitch) ? fmt::format("{:.1f}", pitch) : "straight");
            }
        for (const Json& family : f["families"])
            out += fmt::format("\nThe {} thread: {:.0f} mm on the wall, {:.2f} turns.", family["family"].get<std::string>(), Number(family, "thread_mm"),
                               Number(family, "turns"));
        out += "\n";
    }
    if (m.contains("fittings"))
        out += fmt::format("\n## 6. Fittings\n\nPush fitting_bottom (its {:g} mm port for the air line) and fitting_top into the ends, bond them "
                           "with a silicone adhesive, and clamp over the inserts.\n",
                           Number(m["fittings"], "port_mm"));
    return out;
}

}  // namespace app
