// Colour maps shared by mesh pictures and plots, so a colour bar means the same everywhere.
#pragma once

namespace render {

struct Rgb {
    float r = 0, g = 0, b = 0;
};

// Matplotlib's viridis, sampled: perceptually uniform and readable in grey print. t in [0, 1];
// values outside are clamped, non-finite ones read as 0.
Rgb ViridisColor(double t);

// A diverging map for signed values (Moreland's cool-warm, sampled): blue below the middle, light
// grey at it, red above; a map centred on 0 keeps "contracts" and "lengthens" apart at a glance.
Rgb DivergingColor(double t);

}  // namespace render
