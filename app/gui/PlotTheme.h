#pragma once
// Plots in the desktop's colours: under a dark palette a plot is drawn in dark ink — its
// background, axes, grid, texts, legends, outlines and label boxes (every neutral colour: black,
// grey, white) turned over in lightness — while coloured series, bands and colour maps keep
// their colours. Exports and the command line always draw the light figure, on white.
class QCustomPlot;
class QPalette;

namespace activetouch {

/// Whether `palette` is a dark one: its window colour darker than its text.
bool isDarkPalette(const QPalette& palette);

/// Puts every part of `plot` in dark (true) or light ink. A part in dark ink keeps its light
/// ink, so a call turns only what needs turning (parts added since the last call included) and
/// light → dark → light gives every colour back exactly.
void setDarkInk(QCustomPlot& plot, bool dark);

/// Whether `plot` was last put in dark ink.
bool inDarkInk(const QCustomPlot& plot);

}  // namespace activetouch
