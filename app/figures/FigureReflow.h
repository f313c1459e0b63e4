#pragma once
// A figure's rows of panels at the width it is drawn: as many panels side by side as the width
// holds, the rest wrapped into further lines below in order, so that a narrow figure grows taller
// rather than letting legends and labels run into each other.
class QCustomPlot;
class QCPAxisRect;
class QCPColorScale;
class QCPItemText;

namespace activetouch {

/// A figure row's property: how many of its columns wrap together (a panel and its colour scale
/// beside it: 2); 1 if unset.
inline constexpr const char* kColumnGroup = "columnsKeptTogether";

/// A figure row's property: how many rows of its panels the figure's usual height holds (a figure
/// whose panels' count follows its data); unset, as many as it has.
inline constexpr const char* kUsualRows = "rowsTheUsualHeightHolds";

/// Puts as many columns of each figure row (addFigureRow) side by side as the plot's width holds
/// — a column needs room for its panels' axes and some data, for the widest entry of a legend
/// under it and for a legend inside it beside the axis — and the rest in further lines under
/// them, in their order. Always from the arrangement the figure's code made (kept), so a wider
/// plot puts the panels back. At a `fresh` size it only puts them back as the figure's code made
/// them (the next round measures them there); within the rounds of one size, more panels go to a
/// line only with room to spare, so that the rounds settle. Returns whether any row changed;
/// does not replot. Call after a layout (it measures the margins).
bool reflowPanels(QCustomPlot& plot, bool fresh);

/// How many times taller the figure's rows of panels are after the last reflow than its usual
/// height holds, weighted by their stretch: 1 where nothing wrapped and no row holds more rows
/// of panels than usual (kUsualRows).
double reflowGrowth(const QCustomPlot& plot);

/// `label` sits at the top of `rect`, over the data, whose values reach up to `dataTop` on the
/// left axis (which starts at `bottom`): fitHeadroom raises the top of that axis until the label
/// fits above the data at the panel's size.
void keepTextAboveData(QCPAxisRect* rect, QCPItemText* label, double bottom, double dataTop);

/// Refits every panel set up by keepTextAboveData for its current size. Returns whether any
/// range changed; does not replot. Call after a layout.
bool fitHeadroom(QCustomPlot& plot);

/// Keeps `scale` beside `rect` at the same top and bottom (fitColourScales), as a margin group
/// would; a margin group also holding a colour scale never gives back room it once took.
void alignWithPanel(QCPColorScale* scale, QCPAxisRect* rect);

/// Gives every scale set up by alignWithPanel its panel's top and bottom margins. Returns whether
/// any changed; does not replot. Call after a layout.
bool fitColourScales(QCustomPlot& plot);

/// Marks `label` as naming the data point at its position: placePointLabels puts it beside the
/// point where it covers no data and no other label. It is hidden until a layout places it.
void markPointLabel(QCPItemText* label);

/// Places every label marked by markPointLabel: beside its point, on the first side (right,
/// left, above, below, then the corners) where it covers no plotted point, line or error bar, no
/// label placed before it and stays inside its panel; a label with no such side at the panel's
/// size is hidden (the point stays, and its value is in the figure's data). Returns whether any
/// label moved; does not replot. Call after a layout.
bool placePointLabels(QCustomPlot& plot);

}  // namespace activetouch
