using System.Globalization;
using System.Xml;
using System.Xml.Linq;

namespace LaserEngrave.Core.Vectors;

/// <summary>Reads the geometry of an SVG 1.1 file into millimetre paths, y down.</summary>
/// <remarks>
/// Written here on System.Xml.Linq because no SVG library restores from this machine's package source (Svg,
/// SharpVectors and VectSharp were probed, see docs/dependencies.md), and an engraver needs only the outlines:
/// path, rect, circle, ellipse, line, polyline, polygon, g, use and nested svg, with transforms, viewBox and
/// physical units. Styles are read for display and visibility only (attributes, &lt;style&gt; rules with simple
/// selectors, style attributes; SvgStyleSheet): every visible outline is engraved whatever its stroke or fill. Text is engraved only once converted to paths; &lt;text&gt;, &lt;image&gt; and the like are named in the warnings.
/// </remarks>
public static class SvgReader
{
    private const int MaxUseDepth = 32;

    private static readonly XNamespace Svg = "http://www.w3.org/2000/svg";
    private static readonly XNamespace XLink = "http://www.w3.org/1999/xlink";
    private static readonly XNamespace Inkscape = "http://www.inkscape.org/namespaces/inkscape";

    /// <summary>Elements that only define things other elements use or describe the file: not drawn where they stand.</summary>
    private static readonly HashSet<string> NotDrawn =
    [
        "defs", "symbol", "title", "desc", "metadata", "style", "script", "linearGradient", "radialGradient", "pattern",
        "marker", "clipPath", "mask", "filter", "font", "font-face", "color-profile", "cursor", "view",
    ];

    public static Drawing Read(string path)
    {
        XDocument document;
        try
        {
            CheckShape(path);
            using var stream = File.OpenRead(path);
            using var xml = XmlReader.Create(stream, new XmlReaderSettings { DtdProcessing = DtdProcessing.Ignore, XmlResolver = null });
            document = XDocument.Load(xml, LoadOptions.SetLineInfo);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new DrawingException($"{path}: cannot read the drawing: {ex.Message}", ex);
        }
        catch (XmlException ex)
        {
            throw new DrawingException($"{path}: not well-formed XML: {ex.Message}", ex);
        }

        return Read(document, path);
    }

    public static Drawing Parse(string text, string path)
    {
        try
        {
            using (var reader = new StringReader(text))
            {
                CheckShape(XmlReader.Create(reader, new XmlReaderSettings { DtdProcessing = DtdProcessing.Ignore, XmlResolver = null }), path);
            }

            return Read(XDocument.Parse(text, LoadOptions.SetLineInfo), path);
        }
        catch (XmlException ex)
        {
            throw new DrawingException($"{path}: not well-formed XML: {ex.Message}", ex);
        }
    }

    private static void CheckShape(string path)
    {
        using var stream = File.OpenRead(path);
        CheckShape(XmlReader.Create(stream, new XmlReaderSettings { DtdProcessing = DtdProcessing.Ignore, XmlResolver = null }), path);
    }

    /// <summary>
    /// One streaming pass over the XML before it is loaded: refuses nesting deeper than <see cref="DrawingLimits.MaxNestingDepth"/>
    /// (building the tree of 200 000 nested groups takes minutes) and more elements than the reader may expand.
    /// </summary>
    private static void CheckShape(XmlReader xml, string path)
    {
        using (xml)
        {
            long elements = 0;
            while (xml.Read())
            {
                if (xml.NodeType != XmlNodeType.Element)
                {
                    continue;
                }

                if (xml.Depth > DrawingLimits.MaxNestingDepth)
                {
                    var line = ((IXmlLineInfo)xml).LineNumber;
                    throw DrawingLimits.Exceeded(path, $"line {line}", DrawingLimits.MaxNestingDepth, "levels of nested elements", "flatten the groups in the drawing program");
                }

                if (++elements > DrawingLimits.MaxExpandedEntities)
                {
                    throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxExpandedEntities, "elements", "split the drawing");
                }
            }
        }
    }

    private static Drawing Read(XDocument document, string path)
    {
        var root = document.Root;
        if (root is null || root.Name.LocalName != "svg")
        {
            throw new DrawingException($"{path}: the root element is <{root?.Name.LocalName}>, not <svg>");
        }

        var warnings = new DrawingWarnings();
        var (toMm, stated, viewport) = RootTransform(root, path, warnings);
        var walker = new Walker(path, warnings, document, SvgStyleSheet.Read(document, path)) { Viewport = viewport };
        walker.Children(root, toMm, string.Empty, 0);
        return new Drawing(path, walker.Paths, warnings.ToList(), stated);
    }

    /// <summary>
    /// From the root's user units to millimetres: width and height give the size, viewBox and preserveAspectRatio map user
    /// units into it. Also the root's viewport in user units, what a percentage inside it is of (its viewBox, else its
    /// size; 0 when neither is given).
    /// </summary>
    private static (Affine Transform, bool Stated, (double W, double H) Viewport) RootTransform(XElement root, string path, DrawingWarnings warnings)
    {
        var id = Describe(root, path);
        double? width = Size(root, "width"), height = Size(root, "height");
        var stated = IsPhysical(root.Attribute("width")?.Value) || IsPhysical(root.Attribute("height")?.Value);
        if (!stated)
        {
            warnings.Note("the drawing's width and height are not in physical units: user units read as CSS pixels (96 per inch); give --width-mm to size it");
        }

        var viewBox = root.Attribute("viewBox")?.Value;
        if (viewBox is null)
        {
            return (Affine.Scale(SvgLength.MmPerPx, SvgLength.MmPerPx), stated, ((width ?? 0) / SvgLength.MmPerPx, (height ?? 0) / SvgLength.MmPerPx));
        }

        var box = ViewBox(viewBox, id);

        // Missing sizes follow the viewBox's aspect; both missing means one user unit per CSS pixel.
        var w = width ?? (height is { } h0 ? h0 * box[2] / box[3] : box[2] * SvgLength.MmPerPx);
        var h = height ?? (width is { } w0 ? w0 * box[3] / box[2] : box[3] * SvgLength.MmPerPx);
        return (ViewBoxMap(box, root.Attribute("preserveAspectRatio")?.Value, 0, 0, w, h), stated, (box[2], box[3]));

        double? Size(XElement e, string attribute)
        {
            var text = e.Attribute(attribute)?.Value;
            if (text is null || text.TrimEnd().EndsWith('%'))
            {
                return null;
            }

            var px = SvgLength.UserUnits(text, 0, id, attribute);
            return px > 0 ? px * SvgLength.MmPerPx : throw new DrawingException($"{id}: {attribute}=\"{text}\" must be above 0");
        }

        static bool IsPhysical(string? text) =>
            SvgLength.TrySplit(text, out _, out var unit) && unit is "mm" or "cm" or "in" or "pt" or "pc" or "q";
    }

    /// <summary>A viewBox's four numbers (min-x, min-y, width, height), width and height above 0.</summary>
    private static double[] ViewBox(string viewBox, string id)
    {
        var box = viewBox.Split([' ', ',', '\t', '\n', '\r'], StringSplitOptions.RemoveEmptyEntries)
            .Select(v => double.TryParse(v, NumberStyles.Float, CultureInfo.InvariantCulture, out var d) ? d : double.NaN)
            .ToArray();
        return box.Length != 4 || box.Any(v => !double.IsFinite(v)) || !(box[2] > 0) || !(box[3] > 0)
            ? throw new DrawingException($"{id}: viewBox=\"{viewBox}\" is not four numbers with a width and height above 0")
            : box;
    }

    /// <summary>
    /// The SVG specification's viewBox-to-viewport transform (SVG 1.1, 7.8): <paramref name="box"/> scaled into the
    /// viewport x, y, w, h, uniformly and aligned as preserveAspectRatio says (xMidYMid meet when absent), or stretched for "none".
    /// </summary>
    private static Affine ViewBoxMap(double[] box, string? preserveAspectRatio, double x, double y, double w, double h)
    {
        double sx = w / box[2], sy = h / box[3], tx = 0, ty = 0;
        var aspect = (preserveAspectRatio ?? "xMidYMid meet").Split(' ', StringSplitOptions.RemoveEmptyEntries);
        var align = aspect.FirstOrDefault(a => a != "defer") ?? "xMidYMid";
        if (align != "none")
        {
            var s = aspect.Contains("slice") ? Math.Max(sx, sy) : Math.Min(sx, sy);
            var ax = align.Length >= 4 ? align[..4] : "xMid";
            var ay = align.Length >= 8 ? align[4..8] : "YMid";
            tx = ax switch { "xMin" => 0, "xMax" => w - (box[2] * s), _ => (w - (box[2] * s)) / 2 };
            ty = ay switch { "YMin" => 0, "YMax" => h - (box[3] * s), _ => (h - (box[3] * s)) / 2 };
            sx = sy = s;
        }

        var m = Affine.Compose(Affine.Translate(-box[0], -box[1]), Affine.Scale(sx, sy));
        return Affine.Compose(m, Affine.Translate(x + tx, y + ty));
    }

    private static string Describe(XElement e, string path)
    {
        var line = ((IXmlLineInfo)e).HasLineInfo() ? $" (line {((IXmlLineInfo)e).LineNumber})" : string.Empty;
        var id = e.Attribute("id")?.Value;
        return $"{path}: <{e.Name.LocalName}>{(id is null ? string.Empty : $" id \"{id}\"")}{line}";
    }

    private static string ShortName(XElement e)
    {
        var id = e.Attribute("id")?.Value;
        var line = ((IXmlLineInfo)e).HasLineInfo() ? ((IXmlLineInfo)e).LineNumber : 0;
        return id is null ? $"line {line}" : $"#{id}";
    }

    private sealed class Walker(string path, DrawingWarnings warnings, XDocument document, SvgStyleSheet styles)
    {
        private Dictionary<string, XElement>? _ids;

        /// <summary>The viewport the walk is in, in the current user units: what a percentage is of.</summary>
        public (double W, double H) Viewport { get; set; }

        public List<DrawingPath> Paths { get; } = [];

        public void Children(XElement parent, Affine transform, string layer, int depth)
        {
            foreach (var child in parent.Elements())
            {
                Element(child, transform, layer, depth);
            }
        }

        private long _expanded;

        private long _curves;

        private void Element(XElement e, Affine parent, string layer, int depth)
        {
            // Every element visited counts, each copy a <use> makes included: 4^15 copies are refused, not drawn.
            if (++_expanded > DrawingLimits.MaxExpandedEntities)
            {
                throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxExpandedEntities, "elements once each <use> copy is counted", "<use> copies of copies multiply; use fewer of them");
            }

            if (e.Name.Namespace != Svg && e.Name.Namespace != XNamespace.None)
            {
                // Editor data (sodipodi:namedview, inkscape:*) and foreign objects hold no SVG geometry.
                return;
            }

            var name = e.Name.LocalName;
            if (NotDrawn.Contains(name))
            {
                return;
            }

            var id = Describe(e, path);
            if (Hidden(e))
            {
                warnings.Skipped($"<{name}>", ShortName(e), "hidden (display:none or visibility:hidden)");
                return;
            }

            if (e.Attribute("clip-path") is not null || e.Attribute("mask") is not null)
            {
                warnings.Note($"clip paths and masks are ignored: {id} is engraved unclipped");
            }

            var transform = e.Attribute("transform")?.Value is { } t ? Affine.Compose(SvgTransformList.Parse(t, id), parent) : parent;
            switch (name)
            {
                case "g" or "a" or "switch":
                    var label = e.Attribute(Inkscape + "groupmode")?.Value == "layer"
                        ? e.Attribute(Inkscape + "label")?.Value ?? e.Attribute("id")?.Value ?? layer
                        : layer;
                    Children(e, transform, label, depth);
                    return;
                case "svg":
                    Instance(e, transform, layer, depth, id, Length(e, "x", id, Viewport.W), Length(e, "y", id, Viewport.H), e.Attribute("width")?.Value, e.Attribute("height")?.Value);
                    return;
                case "use":
                    Use(e, transform, layer, depth, id);
                    return;
                case "text" or "flowRoot" or "textPath" or "tspan":
                    warnings.Skipped($"<{name}>", ShortName(e), "text is not engraved; convert it to paths first (Inkscape: Path > Object to Path)");
                    return;
                case "image":
                    warnings.Skipped("<image>", ShortName(e), "bitmaps inside an SVG are not engraved; engrave the image file itself");
                    return;
            }

            var shapes = Shape(e, name, id);
            if (shapes is null)
            {
                warnings.Skipped($"<{name}>", ShortName(e), "not a supported element");
                return;
            }

            foreach (var (curves, closed) in shapes)
            {
                _curves += curves.Count;
                if (Paths.Count >= DrawingLimits.MaxPaths)
                {
                    throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxPaths, "paths (subpaths and shapes)", "split the drawing into files");
                }

                if (_curves > DrawingLimits.MaxCurves)
                {
                    throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxCurves, "segments and curves", "simplify the drawing");
                }

                Paths.Add(new DrawingPath(curves, closed, layer, id[(path.Length + 2)..]).Transform(transform));
            }
        }

        private void Use(XElement e, Affine transform, string layer, int depth, string id)
        {
            var href = (e.Attribute(XLink + "href") ?? e.Attribute("href"))?.Value;
            if (href is null || !href.StartsWith('#'))
            {
                throw new DrawingException($"{id}: href \"{href}\" does not name an element of this file (#id)");
            }

            _ids ??= document.Descendants().Where(d => d.Attribute("id") is not null).GroupBy(d => d.Attribute("id")!.Value).ToDictionary(g => g.Key, g => g.First());
            if (!_ids.TryGetValue(href[1..], out var target))
            {
                throw new DrawingException($"{id}: href \"{href}\" names no element of this file");
            }

            if (depth >= MaxUseDepth)
            {
                throw new DrawingException($"{id}: <use> nested more than {MaxUseDepth} deep (does {href} use itself?)");
            }

            var x = Length(e, "x", id, Viewport.W);
            var y = Length(e, "y", id, Viewport.H);
            if (target.Name.LocalName == "symbol")
            {
                // A symbol is a viewport of its own: the use's width and height (else the symbol's, else 100%) at the use's x and y.
                Instance(target, transform, layer, depth + 1, id, x, y, e.Attribute("width")?.Value ?? target.Attribute("width")?.Value, e.Attribute("height")?.Value ?? target.Attribute("height")?.Value);
            }
            else if (target.Name.LocalName == "svg")
            {
                // A used <svg> takes the use's width and height over its own, and sits at its own x and y inside the use's.
                var placed = Affine.Compose(Affine.Translate(x, y), transform);
                var targetId = Describe(target, path);
                Instance(target, placed, layer, depth + 1, targetId, Length(target, "x", targetId, Viewport.W), Length(target, "y", targetId, Viewport.H), e.Attribute("width")?.Value ?? target.Attribute("width")?.Value, e.Attribute("height")?.Value ?? target.Attribute("height")?.Value);
            }
            else
            {
                Element(target, Affine.Compose(Affine.Translate(x, y), transform), layer, depth + 1);
            }
        }

        /// <summary>
        /// The viewport a nested &lt;svg&gt; or a used &lt;symbol&gt; makes (SVG 1.1, 7.9 and 5.6): at x, y, of width and height
        /// (100% of the viewport it is in when absent), its viewBox mapped into it by its preserveAspectRatio; without a
        /// viewBox its contents keep their units, moved to x, y. Its contents are not clipped to it: what reaches outside is named.
        /// </summary>
        private void Instance(XElement e, Affine parent, string layer, int depth, string id, double x, double y, string? width, string? height)
        {
            var w = SvgLength.UserUnits(width ?? "100%", 0, id, "width", Viewport.W);
            var h = SvgLength.UserUnits(height ?? "100%", 0, id, "height", Viewport.H);
            var viewBox = e.Attribute("viewBox")?.Value is { } text ? ViewBox(text, id) : null;
            if (viewBox is not null && (Viewport.W <= 0 && width is null || Viewport.H <= 0 && height is null))
            {
                // 100% of a viewport of no stated size: the viewBox at one unit per unit, rather than nothing.
                w = width is null ? viewBox[2] : w;
                h = height is null ? viewBox[3] : h;
            }

            if (w < 0 || h < 0)
            {
                throw new DrawingException($"{id}: width {w} and height {h} must not be negative");
            }

            if (viewBox is not null && (w == 0 || h == 0))
            {
                // The specification: a viewport of no width or height draws nothing.
                warnings.Skipped($"<{e.Name.LocalName}>", ShortName(e), "its viewport has no width or height");
                return;
            }

            var map = viewBox is null ? Affine.Translate(x, y) : ViewBoxMap(viewBox, e.Attribute("preserveAspectRatio")?.Value, x, y, w, h);
            var outer = Viewport;
            var first = Paths.Count;
            Viewport = viewBox is null ? (w, h) : (viewBox[2], viewBox[3]);
            try
            {
                Children(e, Affine.Compose(map, parent), layer, depth);
            }
            finally
            {
                Viewport = outer;
            }

            if (w > 0 && h > 0 && Outside(first, parent, x, y, w, h) && e.Attribute("overflow")?.Value.Trim() is not ("visible" or "auto"))
            {
                warnings.Note($"{id}: its contents reach outside its viewport ({x:0.###}, {y:0.###}, {w:0.###} x {h:0.###} user units), which a browser clips; they are engraved unclipped");
            }
        }

        /// <summary>Whether the paths from <paramref name="first"/> on reach outside the viewport x, y, w, h of the parent's units (by the curves' ends: a coarse look).</summary>
        private bool Outside(int first, Affine parent, double x, double y, double w, double h)
        {
            var corners = new[] { new DrawingPoint(x, y), new DrawingPoint(x + w, y), new DrawingPoint(x, y + h), new DrawingPoint(x + w, y + h) }.Select(parent.Apply).ToList();
            double left = corners.Min(c => c.X), right = corners.Max(c => c.X), top = corners.Min(c => c.Y), bottom = corners.Max(c => c.Y);
            var slack = 1e-6 * Math.Max(right - left, bottom - top);
            for (var i = first; i < Paths.Count; i++)
            {
                foreach (var curve in Paths[i].Curves)
                {
                    foreach (var p in (ReadOnlySpan<DrawingPoint>)[curve.Start, curve.End])
                    {
                        if (p.X < left - slack || p.X > right + slack || p.Y < top - slack || p.Y > bottom + slack)
                        {
                            return true;
                        }
                    }
                }
            }

            return false;
        }

        /// <summary>A position attribute in user units; a percentage is of <paramref name="reference"/>, the viewport's width or height.</summary>
        private static double Length(XElement e, string attribute, string id, double reference) =>
            SvgLength.UserUnits(e.Attribute(attribute)?.Value, 0, id, attribute, reference);

        // The cascade for what decides whether an element is drawn: its presentation attribute, then the style
        // sheet's rules, then its own style attribute, each over the one before.
        private bool Hidden(XElement e)
        {
            var display = e.Attribute("display")?.Value.Trim().ToLowerInvariant();
            var visibility = e.Attribute("visibility")?.Value.Trim().ToLowerInvariant();
            display = styles.Value(e, "display") ?? display;
            visibility = styles.Value(e, "visibility") ?? visibility;
            if (e.Attribute("style")?.Value is { } style)
            {
                foreach (var (property, value) in SvgStyleSheet.Declarations(style))
                {
                    if (property == "display")
                    {
                        display = value;
                    }
                    else if (property == "visibility")
                    {
                        visibility = value;
                    }
                }
            }

            return display == "none" || visibility is "hidden" or "collapse";
        }

        private List<(List<IDrawingCurve>, bool)>? Shape(XElement e, string name, string id)
        {
            double L(string attribute, double fallback = 0) => SvgLength.UserUnits(e.Attribute(attribute)?.Value, fallback, id, attribute);

            switch (name)
            {
                case "path":
                    var d = e.Attribute("d")?.Value;
                    if (string.IsNullOrWhiteSpace(d))
                    {
                        warnings.Skipped("<path>", ShortName(e), "no path data (d)");
                        return [];
                    }

                    var subpaths = SvgPathData.Parse(d, id);
                    return subpaths.Count > 0 ? subpaths : Empty("its path data draws nothing (only movetos)");
                case "line":
                    var p0 = new DrawingPoint(L("x1"), L("y1"));
                    var p1 = new DrawingPoint(L("x2"), L("y2"));
                    return p0 == p1 ? Empty("the line has no length") : [([new LineCurve(p0, p1)], false)];
                case "polyline" or "polygon":
                    return Poly(e, name == "polygon", id);
                case "circle":
                    var r = L("r");
                    return r > 0 ? [([EllipticalArcCurve.Circular(new(L("cx"), L("cy")), r, 0, 360)], true)] : Empty("radius is not above 0");
                case "ellipse":
                    double rx = L("rx"), ry = L("ry");
                    return rx > 0 && ry > 0
                        ? [([new EllipticalArcCurve(new(L("cx"), L("cy")), new(rx, 0), new(0, ry), 0, 2 * Math.PI)], true)]
                        : Empty("a radius is not above 0");
                case "rect":
                    return Rect(L("x"), L("y"), L("width"), L("height"), e.Attribute("rx")?.Value is null ? null : L("rx"), e.Attribute("ry")?.Value is null ? null : L("ry"));
                default:
                    return null;
            }

            List<(List<IDrawingCurve>, bool)> Empty(string why)
            {
                warnings.Skipped($"<{name}>", ShortName(e), why);
                return [];
            }

            List<(List<IDrawingCurve>, bool)> Rect(double x, double y, double w, double h, double? rxGiven, double? ryGiven)
            {
                if (w < 0 || h < 0)
                {
                    throw new DrawingException($"{id}: width {w} and height {h} must not be negative");
                }

                if (w == 0 || h == 0)
                {
                    return Empty("width or height is 0");
                }

                var rxr = Math.Min(Math.Abs(rxGiven ?? ryGiven ?? 0), w / 2);
                var ryr = Math.Min(Math.Abs(ryGiven ?? rxGiven ?? 0), h / 2);
                if (rxr == 0 || ryr == 0)
                {
                    DrawingPoint a = new(x, y), b = new(x + w, y), c = new(x + w, y + h), dd = new(x, y + h);
                    return [([new LineCurve(a, b), new LineCurve(b, c), new LineCurve(c, dd), new LineCurve(dd, a)], true)];
                }

                // Clockwise on screen from the end of the top-left corner, each corner a quarter ellipse.
                var curves = new List<IDrawingCurve>();
                var corners = new[]
                {
                    (new DrawingPoint(x + w - rxr, y + ryr), -Math.PI / 2),
                    (new DrawingPoint(x + w - rxr, y + h - ryr), 0.0),
                    (new DrawingPoint(x + rxr, y + h - ryr), Math.PI / 2),
                    (new DrawingPoint(x + rxr, y + ryr), Math.PI),
                };
                DrawingPoint? last = null;
                foreach (var (center, t0) in corners)
                {
                    var arc = new EllipticalArcCurve(center, new(rxr, 0), new(0, ryr), t0, Math.PI / 2);
                    if (last is { } l && l != arc.Start)
                    {
                        curves.Add(new LineCurve(l, arc.Start));
                    }

                    curves.Add(arc);
                    last = arc.End;
                }

                if (last!.Value != curves[0].Start)
                {
                    curves.Add(new LineCurve(last.Value, curves[0].Start));
                }

                return [(curves, true)];
            }
        }

        private List<(List<IDrawingCurve>, bool)> Poly(XElement e, bool closed, string id)
        {
            var text = e.Attribute("points")?.Value ?? string.Empty;
            var values = new List<double>();
            foreach (var token in text.Split([' ', ',', '\t', '\n', '\r'], StringSplitOptions.RemoveEmptyEntries))
            {
                values.Add(double.TryParse(token, NumberStyles.Float, CultureInfo.InvariantCulture, out var v) && double.IsFinite(v)
                    ? v
                    : throw new DrawingException($"{id}: points: \"{token}\" is not a number"));
            }

            if (values.Count % 2 != 0)
            {
                throw new DrawingException($"{id}: points holds {values.Count} numbers, not x,y pairs");
            }

            var points = Enumerable.Range(0, values.Count / 2).Select(i => new DrawingPoint(values[2 * i], values[(2 * i) + 1])).ToList();
            if (closed && points.Count > 1 && points[0] != points[^1])
            {
                points.Add(points[0]);
            }

            var curves = new List<IDrawingCurve>();
            for (var i = 1; i < points.Count; i++)
            {
                if (points[i] != points[i - 1])
                {
                    curves.Add(new LineCurve(points[i - 1], points[i]));
                }
            }

            if (curves.Count == 0)
            {
                warnings.Skipped($"<{e.Name.LocalName}>", ShortName(e), "fewer than two distinct points");
                return [];
            }

            return [(curves, closed || curves[0].Start == curves[^1].End)];
        }
    }
}
