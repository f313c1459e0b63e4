#pragma once
// The SVG documents test_svg_documents reads.
namespace {

inline const char* kDrawing = R"svg(<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">
  <defs><path id="hidden" d="M0 0 H500 V500 H0 Z"/></defs>
  <g transform="rotate(30) translate(10 5)">
    <circle id="c" cx="50" cy="50" r="10"/>
    <rect id="r" x="10" y="10" width="20" height="10" rx="2"/>
    <path id="p" d="M 0 0 L 10 0 L 10 10 Z"/>
    <polyline id="open" points="0,0 5,5 10,0"/>
  </g>
</svg>
)svg";

inline const char* kBadPath = R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="10mm" height="10mm"
     viewBox="0 0 10 10">
  <path id="fine" d="M0 0 H5 V5 Z"/>
  <path id="bad" d="M 0 0 L 10 0 10"/>
</svg>)svg";

inline const char* kInkscape = R"svg(<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"
     xmlns:sodipodi="http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
     width="60mm" height="40mm" viewBox="0 0 60 40" version="1.1">
  <sodipodi:namedview id="view" pagecolor="#ffffff"/>
  <title>a printed plate</title>
  <g inkscape:label="Layer 1" inkscape:groupmode="layer" id="layer1" style="display:inline">
    <rect style="fill:none;stroke:#000000;stroke-width:0.5" id="plate" width="50" height="30"
          x="5" y="5" ry="4"/>
    <text x="10" y="20">label</text>
  </g>
</svg>)svg";

inline const char* kPixels = R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="96" height="48">
<path d="M0 0 L96 0 L96 48 Z"/></svg>)svg";
inline const char* kInches = R"svg(<svg xmlns="http://www.w3.org/2000/svg" width="2in" height="1in"
viewBox="0 0 20 10"><path d="M0 0 H20 V10 H0 Z"/></svg>)svg";

}  // namespace
