#include "report/casting_sheet.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>

namespace app {

namespace {

double Number(const Json& j, const char* key) { return j.contains(key) && j[key].is_number() ? j[key].get<double>() : NAN; }
double Number(const Json& j, size_t index) { return j.is_array() && index < j.size() && j[index].is_number() ? j[index].get<double>() : NAN; }
std::string Text(const Json& j, const char* key) { return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : ""; }

// What each printed file is best printed in: the core as its kind needs, the rest in a rigid plastic.
std::string PrintMaterial(const std::string& file, const std::string& core) {
    if (file.rfind("mold_core", 0) == 0)
        return core == "lost" ? "PVA or BVOH (dissolves in water), or a casting wax" : "PLA or PETG, smooth (sand the layer lines on the cavity's faces)";
    if (file.rfind("fitting", 0) == 0) return "PETG or a tough resin (it carries the clamp)";
    return "PLA or PETG";
}

// Numbered steps: each call is the next.
struct Steps {
    int next = 1;
    std::string Heading(const std::string& title) { return fmt::format("## {}. {}\n\n", next++, title); }
};

// A mold's mixing and pouring, from its entry in the manifest.
std::string MixAndPour(const Json& pour, const std::string& what) {
    const Json& grams = pour["to_mix_g"];
    const Json& ml = pour["silicone_ml"];
    std::string out = fmt::format("Stand the mold {}.\n\n", Text(pour, "orientation"));
    out += fmt::format("**Mix** {:.1f} g of part A and {:.1f} g of part B ({} by weight): {:.1f} ml, for {}'s {:.1f} ml, the sprue's and vents' {:.1f} ml "
                       "and a margin of {} for what stays in the cup and the tube. Mix, scrape the sides, and degas.\n\n",
                       Number(grams, "part_a"), Number(grams, "part_b"), Text(pour, "mix_ratio_a_to_b_by_weight"), Number(ml, "to_mix"), what,
                       Number(ml, "cavity"), Number(ml, "sprue_and_vents"), Text(pour, "margin"));
    const Json& handling = pour["handling"];
    const Json& sprue = pour["sprue"];
    out += fmt::format("**Pour from below.** The sprue is a slot {:.1f} mm across the wall over {:.0f} deg of arc; it carries {:.1f} % of the fill's "
                       "resistance. ",
                       Number(sprue, "across_mm"), Number(sprue, "arc_deg"), 100 * Number(sprue, "share_of_fill_resistance"));
    if (pour.contains("fill")) {
        const Json& fill = pour["fill"];
        const std::string method = Text(fill, "method");
        out += fmt::format("At {:g} cps ({}) the cavity fills in about {:.1f} min from a funnel whose level is {:g} mm above the block's top, "
                           "through a tube into the sprue, or in {:.1f} min from a syringe pushed at {:g} kPa. ",
                           Number(handling, "mixed_viscosity_cps"), Text(handling, "source"), Number(fill, "gravity_min"), Number(fill, "funnel_above_top_mm"),
                           Number(fill, "syringe_min"), Number(fill, "syringe_kpa"));
        if (method == "gravity") out += fmt::format("The pot life is {:g} min: pour by gravity.", Number(handling, "pot_life_min"));
        else if (method == "syringe") out += fmt::format("The pot life is {:g} min: gravity is too slow; use the syringe.", Number(handling, "pot_life_min"));
        else if (method == "too slow")
            out += fmt::format("**The pot life is {:g} min: even the syringe needs more than half of it.** Use a slower version of the silicone, a "
                               "thinner, or a wider wall.",
                               Number(handling, "pot_life_min"));
        out += "\n\n";
    } else {
        out += Text(handling, "source") + ".\n\n";
    }
    out += "Fill until silicone rises out of all four vents, then close the sprue (tape or a plug) and leave the mold upright. ";
    if (handling.contains("cure_h") && handling["cure_h"].is_number())
        out += fmt::format("Cure {:g} h at room temperature (the bulletin's time).", Number(handling, "cure_h"));
    return out + "\n\n";
}

}  // namespace

std::string CastingSheet(const Json& m) {
    const Json& silicone = m["silicone"];
    const Json& core = m["core"];
    const std::string coreKind = Text(core, "kind");
    const bool twoStages = m.contains("first_stage");
    Steps steps;
    std::string out = fmt::format("# Casting the actuator\n\nA wall of {:g} mm ({} on the design's surface), {:.1f} g of {} in the part{}. Lengths in mm.\n\n",
                                  Number(m["part"], "wall_mm"), Text(m["part"], "wall"), Number(silicone, "mass_g"), Text(silicone, "material"),
                                  twoStages ? ", cast in two stages around its fibres" : "");
    out += steps.Heading("Print");
    out += "| file | orientation | size on the bed (mm) | fits the printer | print in |\n|---|---|---|---|---|\n";
    for (const Json& f : m["files"]) {
        const std::string file = Text(f, "file");
        if (!f["print"].contains("size_mm")) continue;  // cast, not printed
        const Json& size = f["print"]["size_mm"];
        out += fmt::format("| {} | {} | {:.0f} x {:.0f} x {:.0f} | {} | {} |\n", file, Text(f["print"], "orientation"), size[0].get<double>(),
                           size[1].get<double>(), size[2].get<double>(), f["print"]["fits_printer"].get<bool>() ? "yes" : "**no**",
                           PrintMaterial(file, coreKind));
    }
    out += fmt::format("\nThe printer's build volume: {:g} x {:g} x {:g}.\n\n", m["printer_mm"][0].get<double>(), m["printer_mm"][1].get<double>(),
                       m["printer_mm"][2].get<double>());
    out += steps.Heading("Prepare");
    out += "Clear every sprue (shell A's bottom end wall), the four vents of each mold (the top end wall) and the core's channels of "
           "stringing. Coat the cavity faces and the core with a release agent for platinum silicone. Keep sulphur clays, latex and "
           "uncured resin prints away from the silicone: they inhibit its cure.\n\n";
    const Json& support = core["support"];
    if (support.contains("how")) {
        std::string heights;
        for (const Json& s : support["spacers"]) heights += fmt::format("{}{:.0f}", heights.empty() ? "" : ", ", Number(s, "z_mm"));
        std::string how = Text(support, "how");
        if (!how.empty()) how[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(how[0])));
        out += fmt::format("**Spacers.** The core is {:.1f} mm across at its thinnest, {:.0f} times as long: held only at its ends it could bend {:.2f} mm "
                           "under the fill's head, more than a tenth of the wall. {}: at heights {} mm, at 30, 150 and 270 deg.\n\n",
                           Number(support, "thinnest_mm"), Number(support, "slenderness"), Number(support, "deflection_mm"), how, heights);
    }
    const std::string close = "lay the core in shell B, its handles in the end walls' channels; close shell A over it, pins into holes, and "
                              "clamp or tape the halves together along their length.";
    if (twoStages) {
        const Json& first = m["first_stage"];
        out += steps.Heading("First stage: the inner layer");
        out += fmt::format("Into stage1_shell_b and stage1_shell_a: {} The cavity is the wall's inner {:g} mm, its ribs the guide grooves.\n\n", close,
                           Number(first, "layer_mm"));
        out += MixAndPour(first["pour"], "the layer");
        out += "Open the first stage's shells and leave the layer on the core.\n\n";
        const Json& f = m["fibres"];
        out += steps.Heading("Wind the fibres");
        out += fmt::format("{} ({:g} N/mm per family): {}. Winding order: {}.\n\n", Text(f, "layout"), Number(f, "stiffness_n_per_mm"), Text(f, "how"),
                           Text(f, "order"));
        out += "| family | hand | band (mm from the bottom) | angle to the meridian (deg) | turns | pitch (mm per turn) |\n|---|---|---|---|---|---|\n";
        for (const Json& family : f["families"])
            for (const Json& b : family["bands"]) {
                const double angle = Number(b, "angle_deg"), pitch = Number(b, "pitch_mm");
                out += fmt::format("| {} | {} | {:.1f} to {:.1f} | {} | {:.2f} | {} |\n", Text(family, "family"), Text(family, "hand"), Number(b, "from_mm"),
                                   Number(b, "to_mm"), std::isfinite(angle) ? fmt::format("{:.1f}", angle) : "by sector", Number(b, "turns"),
                                   std::isfinite(pitch) ? fmt::format("{:.1f}", pitch) : "straight");
            }
        for (const Json& family : f["families"]) {
            std::string starts;
            for (const Json& a : family["start_angles_deg"]) starts += fmt::format("{}{:.0f}", starts.empty() ? "" : ", ", a.get<double>());
            out += fmt::format("\nThe {} family: {} threads, each {:.0f} mm on the wall and {:.2f} turns, starting at {} deg on the bottom end; "
                               "{:.1f} to {:.1f} mm apart across; each thread of EA {:.0f} N (its stiffness, force per unit strain) is the "
                               "model's {:g} N/mm family at the mean spacing.",
                               Text(family, "family"), family["threads"].get<int>(), Number(family, "thread_mm"), Number(family, "turns"), starts,
                               Number(family["spacing_mm"], size_t{0}), Number(family["spacing_mm"], size_t{1}), Number(family, "ea_per_thread_n"),
                               Number(f, "stiffness_n_per_mm"));
        }
        out += " Tie each thread off at the ends, where the clamps will hold it. winding_guides.png shows the grooves and the threads.\n\n";
        out += steps.Heading("Second stage: the overmould");
        out += "Into mold_shell_b and mold_shell_a, the core with its wound layer: " + close + "\n\n";
        out += MixAndPour(m["pour"], "the wall's outer part");
    } else if (m.contains("halves")) {
        const Json& halves = m["halves"];
        for (const Json& piece : halves["pieces"]) {
            const std::string half = Text(piece, "half");
            out += steps.Heading("The " + half + " half");
            out += fmt::format("Into {0}_mold_shell_b and {0}_mold_shell_a, {0}_mold_core: {1} The cavity is the wall from z = {2:.1f} to {3:.1f} mm, "
                               "its flange at the cut.\n\n",
                               half, close, Number(piece, "from_mm"), Number(piece, "to_mm"));
            out += MixAndPour(piece["pour"], "the " + half + " half");
            out += fmt::format("Open the shells and pull {}_mold_core out through the cut ({} end, a hoop stretch of {:.2f}).\n\n", half,
                               Text(piece, "core_exit"), Number(piece, "demoulding_stretch"));
        }
        out += steps.Heading("Bond the halves");
        std::string bond = Text(halves, "bond");
        if (!bond.empty()) bond[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(bond[0])));
        out += bond + ". Trim the sprues' and vents' tabs. Test it under water at a low pressure before use: the bond is its weakest line.\n";
    } else {
        out += steps.Heading("Assemble, mix and pour");
        std::string sentence = close;
        sentence[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(sentence[0])));
        out += sentence + "\n\n" + MixAndPour(m["pour"], "the cavity");
    }
    if (!m.contains("halves")) {
        out += steps.Heading("Demould");
        std::string how = Text(core, "how");
        if (!how.empty()) how[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(how[0])));
        out += "Open the shells along the split plane. " + how + ". Trim the sprue's and the vents' tabs from the ends.\n";
    }
    if (m.contains("fittings")) {
        out += "\n" + steps.Heading("Fittings");
        out += fmt::format("Push fitting_bottom (its {:g} mm port for the air line) and fitting_top into the ends, bond them with a silicone adhesive, "
                           "and clamp over the inserts.\n",
                           Number(m["fittings"], "port_mm"));
    }
    return out;
}

}  // namespace app
