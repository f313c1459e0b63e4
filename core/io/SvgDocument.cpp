#include "core/io/SvgDocument.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <array>
#include <boost/mpl/set.hpp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <svgpp/policy/xml/libxml2.hpp>
#include <svgpp/svgpp.hpp>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"

namespace activetouch {

std::string SvgElement::name() const {
    return kind + (id.empty() ? std::string() : " '" + id + "'") + " (line " +
           std::to_string(line) + ")";
}

namespace {

namespace mpl = boost::mpl;
namespace tag = svgpp::tag;

constexpr const char* kSvgNamespace = "http://www.w3.org/2000/svg";
/// A user unit (a CSS pixel, 1/96 in) in mm: SVG++ maps every length and viewBox into these.
constexpr double kMmPerUserUnit = 25.4 / 96.0;

using Matrix = std::array<double, 6>;  ///< a b c d e f, as SVG's matrix()

Matrix times(const Matrix& p, const Matrix& q) {
    return {p[0] * q[0] + p[2] * q[1],        p[1] * q[0] + p[3] * q[1],
            p[0] * q[2] + p[2] * q[3],        p[1] * q[2] + p[3] * q[3],
            p[0] * q[4] + p[2] * q[5] + p[4], p[1] * q[4] + p[3] * q[5] + p[5]};
}

/// What the traversal collects, and where it is (for messages).
struct Collected {
    std::vector<SvgElement> elements;
    std::vector<std::pair<std::string, int>> order;  ///< each drawn element's kind and line
    std::size_t entered = 0;                         ///< elements entered so far
};

/// One element's context: the transform from its user space into the document's, and the path
/// it draws. Child elements get a context of their own, starting from their parent's transform.
class Context {
public:
    /// The document's svg element: the first entered.
    explicit Context(Collected& c) : collected_(c), index_(c.entered++) {}
    /// Each drawn child, in document order as SVG++ enters it.
    Context(Context& parent)
        : collected_(parent.collected_), matrix_(parent.matrix_), index_(collected_.entered++) {}

    template <class ElementTag>
    void on_enter_element(ElementTag) {}
    void on_exit_element() {
        if (current_.empty() && subpaths_.empty()) return;
        endSubpath();
        SvgElement e;
        if (index_ < collected_.order.size()) {
            e.kind = collected_.order[index_].first;
            e.line = collected_.order[index_].second;
        }
        e.id = id_;
        e.subpaths = std::move(subpaths_);
        e.toMm = matrix_;
        for (double& v : e.toMm) v *= kMmPerUserUnit;
        collected_.elements.push_back(std::move(e));
    }
    void transform_matrix(const boost::array<double, 6>& t) {
        matrix_ = times(matrix_, {t[0], t[1], t[2], t[3], t[4], t[5]});
    }
    template <class Range>
    void set(tag::attribute::id, const Range& r) {
        id_.assign(r.begin(), r.end());
    }
    void set_viewport(double, double, double, double) {}
    void set_viewbox_size(double, double) {}
    void disable_rendering() { disabled_ = true; }

    void path_move_to(double x, double y, tag::coordinate::absolute) {
        endSubpath();
        add("M", {x, y});
    }
    void path_line_to(double x, double y, tag::coordinate::absolute) { add("L", {x, y}); }
    void path_quadratic_bezier_to(double x1, double y1, double x, double y,
                                  tag::coordinate::absolute) {
        add("Q", {x1, y1, x, y});
    }
    void path_cubic_bezier_to(double x1, double y1, double x2, double y2, double x, double y,
                              tag::coordinate::absolute) {
        add("C", {x1, y1, x2, y2, x, y});
    }
    void path_elliptical_arc_to(double rx, double ry, double rotation, bool large, bool sweep,
                                double x, double y, tag::coordinate::absolute) {
        add("A", {rx, ry, rotation, large ? 1.0 : 0.0, sweep ? 1.0 : 0.0, x, y});
    }
    void path_close_subpath() {
        if (!disabled_) current_ += " Z";
        endSubpath();
    }
    void path_exit() {}

private:
    /// A command in the element's own user space, written as SVG path data reads it.
    void add(const char* command, std::initializer_list<double> numbers) {
        if (disabled_) return;
        current_ += current_.empty() ? "" : " ";
        current_ += command;
        char text[40];
        for (double v : numbers) {
            std::snprintf(text, sizeof text, " %.17g", v);
            current_ += text;
        }
    }
    void endSubpath() {
        if (!current_.empty()) subpaths_.push_back(std::move(current_));
        current_.clear();
    }

    Collected& collected_;
    Matrix matrix_{1, 0, 0, 1, 0, 0};
    std::size_t index_ = 0;
    std::string id_, current_;
    std::vector<std::string> subpaths_;
    bool disabled_ = false;
};

struct ChildContextFactories {
    template <class ParentContext, class ElementTag, class Enable = void>
    struct apply {
        typedef svgpp::factory::context::on_stack<Context> type;
    };
};

typedef mpl::set<tag::element::svg, tag::element::g, tag::element::path, tag::element::rect,
                 tag::element::circle, tag::element::ellipse, tag::element::polygon,
                 tag::element::polyline, tag::element::line>::type DrawnElements;

typedef mpl::fold<mpl::protect<mpl::joint_view<svgpp::traits::shapes_attributes_by_element,
                                               svgpp::traits::viewport_attributes>>,
                  mpl::set<tag::attribute::transform, tag::attribute::id>::type,
                  mpl::insert<mpl::_1, mpl::_2>>::type ReadAttributes;

bool isDrawnKind(const char* name) {
    for (const char* k :
         {"svg", "g", "path", "rect", "circle", "ellipse", "polygon", "polyline", "line"})
        if (std::strcmp(name, k) == 0) return true;
    return false;
}

/// The elements SVG++ will enter, in its order: SVG elements of the drawn kinds, their children
/// only for svg and g.
void listDrawn(xmlNode* node, std::vector<std::pair<std::string, int>>& out) {
    const char* name = reinterpret_cast<const char*>(node->name);
    const bool svg = node->ns && node->ns->href &&
                     std::strcmp(reinterpret_cast<const char*>(node->ns->href), kSvgNamespace) == 0;
    if (node->type != XML_ELEMENT_NODE || !svg || !isDrawnKind(name)) return;
    out.emplace_back(name, static_cast<int>(xmlGetLineNo(node)));
    if (std::strcmp(name, "svg") != 0 && std::strcmp(name, "g") != 0) return;
    for (xmlNode* child = node->children; child; child = child->next) listDrawn(child, out);
}

/// "path 'gear' (line 12)" for a node of the document.
std::string describeNode(const xmlNode* node) {
    SvgElement e;
    e.kind = reinterpret_cast<const char*>(node->name);
    e.line = static_cast<int>(xmlGetLineNo(node));
    if (xmlChar* id = xmlGetProp(node, reinterpret_cast<const xmlChar*>("id"))) {
        e.id = reinterpret_cast<const char*>(id);
        xmlFree(id);
    }
    return e.name();
}

}  // namespace

std::vector<SvgElement> readSvgDocument(const std::string& path, const std::string& source,
                                        const std::string& place) {
    const std::string text = readBoundedFile(path, kMaxSvgFileBytes, "an SVG document");
    std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc(
        xmlReadMemory(text.data(), static_cast<int>(text.size()), path.c_str(), nullptr,
                      XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING),
        &xmlFreeDoc);
    if (!doc) {
        const xmlError* e = xmlGetLastError();
        throw InputError(source, place,
                         "'" + path + "' is not XML" +
                             (e ? " (line " + std::to_string(e->line) + ": " +
                                      std::string(e->message ? e->message : "") + ")"
                                : std::string()) +
                             "; give an SVG document");
    }
    xmlNode* root = xmlDocGetRootElement(doc.get());
    Collected collected;
    if (root) listDrawn(root, collected.order);
    if (collected.order.empty() || collected.order.front().first != "svg")
        throw InputError(source, place,
                         "'" + path + "' is XML but no SVG document (its root is no svg element)");
    Context context(collected);
    try {
        svgpp::document_traversal<
            svgpp::processed_elements<DrawnElements>, svgpp::processed_attributes<ReadAttributes>,
            svgpp::context_factories<ChildContextFactories>,
            svgpp::basic_shapes_policy<svgpp::policy::basic_shapes::all_to_path>,
            svgpp::path_policy<svgpp::policy::path::no_shorthands>,
            svgpp::viewport_policy<svgpp::policy::viewport::as_transform>>::load_document(root,
                                                                                          context);
    } catch (const boost::exception& e) {
        // SVG++ names the element it was reading when it failed.
        using ElementInfo = boost::error_info<tag::error_info::xml_element, xmlNode*>;
        const xmlNode* const* node = boost::get_error_info<ElementInfo>(e);
        const auto* reason = dynamic_cast<const std::exception*>(&e);
        throw InputError(source, place,
                         "'" + path + "' cannot be read" +
                             (node && *node ? " at the " + describeNode(*node) : std::string()) +
                             ": " + (reason ? reason->what() : "an unreadable element") +
                             "; fix that element or leave it out of the file");
    } catch (const std::exception& e) {
        throw InputError(source, place, "'" + path + "' cannot be read: " + e.what());
    }
    return std::move(collected.elements);
}

}  // namespace activetouch
