using System.Globalization;

namespace LaserEngrave.Core.Vectors;

/// <summary>Reads the 2D geometry of an ASCII DXF file (R12 to current) into millimetre paths, y down.</summary>
/// <remarks>
/// Written here because no DXF library restores from this machine's package source (netDxf, IxMilia.Dxf and ACadSharp
/// were probed, see docs/dependencies.md), and an engraver needs only the geometry: LINE, LWPOLYLINE and POLYLINE with
/// bulges, ARC, CIRCLE, ELLIPSE, SPLINE, and INSERTs of blocks (scaled, rotated, arrayed, nested). Everything else
/// (TEXT, HATCH, DIMENSION, meshes ...) is counted and named in the warnings, never dropped silently.
/// </remarks>
public static class DxfReader
{
    private const int MaxBlockDepth = 32;

    /// <summary>$INSUNITS codes and the millimetres in one unit.</summary>
    private static readonly Dictionary<int, (double Mm, string Name)> Units = new()
    {
        [1] = (25.4, "inches"),
        [2] = (304.8, "feet"),
        [3] = (1_609_344, "miles"),
        [4] = (1, "millimetres"),
        [5] = (10, "centimetres"),
        [6] = (1000, "metres"),
        [7] = (1_000_000, "kilometres"),
        [8] = (25.4e-6, "microinches"),
        [9] = (0.0254, "mils"),
        [10] = (914.4, "yards"),
        [11] = (1e-7, "angstroms"),
        [12] = (1e-6, "nanometres"),
        [13] = (1e-3, "microns"),
        [14] = (100, "decimetres"),
        [15] = (10_000, "decametres"),
        [16] = (100_000, "hectometres"),
        [21] = (1_200_000 / 3937.0, "US survey feet"),
        [22] = (100_000 / 3937.0, "US survey inches"),
        [23] = (3_600_000 / 3937.0, "US survey yards"),
    };

    public static Drawing Read(string path)
    {
        try
        {
            // Read as it comes (DxfLines), with the encoding File.ReadAllText would have found: UTF-8 unless a byte order mark says otherwise.
            return Parse(() => new StreamReader(path, System.Text.Encoding.UTF8, detectEncodingFromByteOrderMarks: true), path);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new DrawingException($"{path}: cannot read the drawing: {ex.Message}", ex);
        }
    }

    public static Drawing Parse(string text, string path)
    {
        ArgumentNullException.ThrowIfNull(text);
        return Parse(() => new StringReader(text), path);
    }

    private static Drawing Parse(Func<TextReader> open, string path)
    {
        using (var text = open())
        {
            if (Parse(text, path, streamEntities: true) is { } drawing)
            {
                return drawing;
            }
        }

        // A HEADER, TABLES or BLOCKS section after the entities (not the order DXF writes them in): read again, keeping
        // every entity until the whole file is read, since a layer or block defined further on changes them.
        using var again = open();
        return Parse(again, path, streamEntities: false)!;
    }

    // Null when the entities were converted as they came and a section after them could have changed them.
    private static Drawing? Parse(TextReader text, string path, bool streamEntities)
    {
        var lines = new DxfLines(text);
        if (lines.MoveNext() && lines.Current.StartsWith("AutoCAD Binary DXF", StringComparison.Ordinal))
        {
            throw new DrawingException($"{path}: binary DXF is not read; save the drawing as ASCII DXF");
        }

        var stream = streamEntities ? new EntityStream(path) : null;
        var file = Structure(Groups(lines, path), path, stream);
        if (stream is { Abandoned: true })
        {
            return null;
        }

        if (stream is { Started: true })
        {
            return stream.Finish();
        }

        var warnings = new DrawingWarnings();
        var mm = Millimetres(file, warnings, path, out var unitsStated);

        // DXF's y grows up; the stage's and LaserEngrave's grow down.
        var toMm = Affine.Scale(mm, -mm);
        var reader = new Converter(file, warnings, path);
        foreach (var entity in file.Entities)
        {
            reader.Convert(entity, toMm, inheritedLayer: null, depth: 0);
        }

        return new Drawing(path, reader.Paths, warnings.ToList(), unitsStated);
    }

    // The millimetres in one drawing unit ($INSUNITS), noting a drawing that states none.
    private static double Millimetres(DxfFile file, DrawingWarnings warnings, string path, out bool unitsStated)
    {
        unitsStated = file.InsUnits is { } u && Units.ContainsKey(u);
        if (unitsStated)
        {
            return Units[file.InsUnits!.Value].Mm;
        }

        if (file.InsUnits is null or 0)
        {
            warnings.Note("the drawing states no units ($INSUNITS): read as millimetres; give --width-mm to size it");
            return 1;
        }

        throw new DrawingException($"{path}: $INSUNITS {file.InsUnits} is not a unit of length LaserEngrave knows");
    }

    /// <summary>
    /// The ENTITIES section converted as it is read, each entity dropped once its paths are made: 300 000 LINEs kept as
    /// their group codes until the end of the file were 120 MiB (issue 38). It starts when the entities do, with the
    /// header's units, the layers and the blocks read before them (the order DXF writes its sections in); a section of
    /// those after the entities abandons it, and the file is read again the old way.
    /// </summary>
    /// <remarks>
    /// What is reported stays what reading the whole file first reported: a line that is not a group code or a
    /// structure error anywhere in the file comes before an error in converting an entity, so that error is kept
    /// until the end of the file; an $INSUNITS that is no unit leaves the entities to be kept, and reported after.
    /// </remarks>
    private sealed class EntityStream(string path)
    {
        private DrawingWarnings? _warnings;
        private Converter? _converter;
        private Affine _toMm;
        private bool _unitsStated;
        private DxfEntity? _last;
        private DrawingException? _failure;

        public bool Started => _converter is not null;

        public bool Abandoned { get; private set; }

        /// <summary>Starts with the entities' section: false when the header's units are no unit (nothing is streamed then).</summary>
        public bool Start(DxfFile file)
        {
            if (file.InsUnits is { } u && u != 0 && !Units.ContainsKey(u))
            {
                return false;
            }

            _warnings = new DrawingWarnings();
            var mm = Millimetres(file, _warnings, path, out _unitsStated);
            _toMm = Affine.Scale(mm, -mm);
            _converter = new Converter(file, _warnings, path);
            return true;
        }

        public void Abandon() => Abandoned = true;

        /// <summary>Takes the next entity of the section: a POLYLINE's VERTEXes join it, its SEQEND is dropped (as Add does).</summary>
        public void Add(DxfEntity entity)
        {
            if (entity.Type == "VERTEX" && _last?.Type == "POLYLINE")
            {
                _last.Children.Add(entity);
                return;
            }

            if (entity.Type is "SEQEND" or "VERTEX" && _last?.Type is "POLYLINE" or "INSERT" or "ATTRIB")
            {
                return;
            }

            ConvertLast();
            _last = entity;
        }

        public Drawing Finish()
        {
            ConvertLast();
            return _failure is not null
                ? throw _failure
                : new Drawing(path, _converter!.Paths, _warnings!.ToList(), _unitsStated);
        }

        // The entity before is complete once the next one is not one of its VERTEXes.
        private void ConvertLast()
        {
            if (_last is null || _failure is not null)
            {
                _last = null;
                return;
            }

            try
            {
                _converter!.Convert(_last, _toMm, inheritedLayer: null, depth: 0);
            }
            catch (DrawingException ex)
            {
                _failure = ex;
            }

            _last = null;
        }
    }

    // The group code / value pairs, each value trimmed, with its line number. The lines come already moved onto the
    // first (the binary check looks at it).
    private static IEnumerable<(int Code, string Value, int Line)> Groups(DxfLines lines, string path)
    {
        var values = new ValueStrings();
        for (var more = lines.Number > 0; more; more = lines.MoveNext())
        {
            var codeLine = lines.Number;
            var codeText = lines.Current.Trim();
            var isCode = int.TryParse(codeText, NumberStyles.Integer, CultureInfo.InvariantCulture, out var code);
            var notCode = isCode ? null : Shorten(codeText.ToString());
            if (!lines.MoveNext())
            {
                throw new DrawingException($"{path}: line {codeLine}: group code without a value (the file is cut short)");
            }

            if (notCode is not null)
            {
                throw new DrawingException($"{path}: line {codeLine}: \"{notCode}\" is not a DXF group code; is this an ASCII DXF file?");
            }

            yield return (code, values.Get(code, lines.Current.Trim()), lines.Number);
        }
    }

    /// <summary>
    /// The values as strings, one string for each repeated word: entity types, layer names, subclass markers and flags
    /// repeat on every entity of a large drawing; coordinates almost never do, so they are not looked up.
    /// </summary>
    private sealed class ValueStrings
    {
        private const int MaxKept = 4096;
        private readonly Dictionary<string, string> _kept = [];
        private readonly Dictionary<string, string>.AlternateLookup<ReadOnlySpan<char>> _lookup;

        public ValueStrings() => _lookup = _kept.GetAlternateLookup<ReadOnlySpan<char>>();

        public string Get(int code, ReadOnlySpan<char> value)
        {
            // Group codes 10-59: coordinates, distances, angles.
            if (code is >= 10 and <= 59 || value.Length > 64)
            {
                return value.ToString();
            }

            if (_lookup.TryGetValue(value, out var kept))
            {
                return kept;
            }

            var text = value.ToString();
            if (_kept.Count < MaxKept)
            {
                _kept[text] = text;
            }

            return text;
        }
    }

    private static string Shorten(string s) => s.Length > 40 ? s[..40] + "..." : s;

    private static DxfFile Structure(IEnumerable<(int Code, string Value, int Line)> source, string path, EntityStream? stream)
    {
        using var groups = source.GetEnumerator();
        try
        {
            return Structure(groups, path, stream);
        }
        catch (DrawingException)
        {
            // Every line is read before the structure is judged, as when the file was split whole first: a line
            // that is not a group code further on is the error to report.
            while (groups.MoveNext())
            {
            }

            throw;
        }
    }

    private static DxfFile Structure(IEnumerator<(int Code, string Value, int Line)> groups, string path, EntityStream? stream)
    {
        var file = new DxfFile();
        string? section = null;
        DxfBlock? block = null;
        var sawSection = false;
        var body = new List<(int, string, int)>();
        var more = groups.MoveNext();
        while (more)
        {
            var (code, value, line) = groups.Current;
            if (code != 0)
            {
                more = groups.MoveNext();
                continue;
            }

            // One entity or table record: everything up to the next group code 0, kept in a list of its own size.
            body.Clear();
            while ((more = groups.MoveNext()) && groups.Current.Code != 0)
            {
                body.Add(groups.Current);
            }

            var entity = new DxfEntity(path, value, line, [.. body]);
            switch (value)
            {
                case "SECTION":
                    section = entity.Text(2);
                    sawSection = true;
                    if (stream is { Started: true } && section is "HEADER" or "TABLES" or "BLOCKS")
                    {
                        stream.Abandon();
                        return file;
                    }

                    if (stream is { Started: false } && section == "ENTITIES" && !stream.Start(file))
                    {
                        stream = null;
                    }

                    if (section == "HEADER")
                    {
                        // The header's variables are code 9 / value pairs with no code 0 between them: all in this body.
                        for (var j = 0; j + 1 < body.Count; j++)
                        {
                            if (body[j].Item1 == 9 && body[j].Item2 == "$INSUNITS")
                            {
                                file.InsUnits = int.TryParse(body[j + 1].Item2, NumberStyles.Integer, CultureInfo.InvariantCulture, out var u)
                                    ? u
                                    : throw new DrawingException($"{path}: line {body[j + 1].Item3}: $INSUNITS \"{body[j + 1].Item2}\" is not a number");
                            }
                        }
                    }

                    continue;
                case "ENDSEC":
                    section = null;
                    continue;
                case "EOF":
                    // Nothing after it is drawn, but every line is still read (a line that is not a group code is still an error).
                    while (groups.MoveNext())
                    {
                    }

                    more = false;
                    continue;
            }

            switch (section)
            {
                case "TABLES" when value == "LAYER":
                    var name = entity.Text(2) ?? string.Empty;
                    var hidden = (entity.Integer(70, 0) & 1) != 0 || entity.Integer(62, 7) < 0;
                    file.Layers[name] = hidden;
                    break;
                case "BLOCKS" when value == "BLOCK":
                    block = new DxfBlock(entity.Text(2) ?? string.Empty, new DrawingPoint(entity.Number(10, 0), entity.Number(20, 0)));
                    file.Blocks[block.Name] = block;
                    break;
                case "BLOCKS" when value == "ENDBLK":
                    block = null;
                    break;
                case "BLOCKS":
                    if (block is null)
                    {
                        throw new DrawingException($"{path}: {entity.Id}: entity outside a BLOCK in the BLOCKS section");
                    }

                    Add(block.Entities, entity);
                    break;
                case "ENTITIES" when stream is not null:
                    stream.Add(entity);
                    break;
                case "ENTITIES":
                    Add(file.Entities, entity);
                    break;
            }
        }

        if (!sawSection)
        {
            throw new DrawingException($"{path}: no SECTION found; not a DXF file");
        }

        return file;
    }

    /// <summary>Adds an entity, attaching VERTEXes to the POLYLINE before them and dropping the SEQEND that closes it.</summary>
    private static void Add(List<DxfEntity> entities, DxfEntity entity)
    {
        if (entity.Type == "VERTEX" && entities.Count > 0 && entities[^1].Type == "POLYLINE")
        {
            entities[^1].Children.Add(entity);
            return;
        }

        if (entity.Type is "SEQEND" or "VERTEX" && entities.Count > 0 && entities[^1].Type is "POLYLINE" or "INSERT" or "ATTRIB")
        {
            return;
        }

        entities.Add(entity);
    }

    private sealed class DxfFile
    {
        public int? InsUnits { get; set; }

        /// <summary>Layer name to whether it is off or frozen.</summary>
        public Dictionary<string, bool> Layers { get; } = new(StringComparer.OrdinalIgnoreCase);

        public Dictionary<string, DxfBlock> Blocks { get; } = new(StringComparer.OrdinalIgnoreCase);

        public List<DxfEntity> Entities { get; } = [];
    }

    private sealed record DxfBlock(string Name, DrawingPoint BasePoint)
    {
        public List<DxfEntity> Entities { get; } = [];
    }

    private sealed class Converter(DxfFile file, DrawingWarnings warnings, string path)
    {
        private long _expanded;

        private long _curves;

        public List<DrawingPath> Paths { get; } = [];

        public void Convert(DxfEntity e, Affine transform, string? inheritedLayer, int depth)
        {
            // Every entity converted counts, each copy an INSERT (its array, its nested blocks) makes included.
            if (++_expanded > DrawingLimits.MaxExpandedEntities)
            {
                throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxExpandedEntities, "entities once INSERTs are expanded (arrays and nested blocks)", "blocks inserted into blocks multiply; nest fewer");
            }

            var layer = e.Layer == "0" && inheritedLayer is not null ? inheritedLayer : e.Layer;
            if (e.Integer(67, 0) == 1)
            {
                warnings.Skipped(e.Type, e.ShortId, "in paper space (only model space is engraved)");
                return;
            }

            if (file.Layers.TryGetValue(layer, out var hidden) && hidden)
            {
                warnings.Skipped(e.Type, e.ShortId, $"on layer \"{layer}\", which is off or frozen");
                return;
            }

            if (e.Type is "LINE" or "ELLIPSE" or "SPLINE")
            {
                // These are in world coordinates; only their z is left out.
                Emit(Build(e), transform, layer, e);
                return;
            }

            if (e.Type is "LWPOLYLINE" or "POLYLINE" or "ARC" or "CIRCLE" or "INSERT")
            {
                if (!InPlane(e, out var mirror))
                {
                    warnings.Skipped(e.Type, e.ShortId, "not in the XY plane (extrusion direction is not ±Z)");
                    return;
                }

                var local = mirror ? Affine.Compose(Affine.Scale(-1, 1), transform) : transform;
                if (e.Type == "INSERT")
                {
                    Insert(e, local, layer, depth);
                }
                else
                {
                    Emit(Build(e), local, layer, e);
                }

                return;
            }

            var why = e.Type switch
            {
                "TEXT" or "MTEXT" or "ATTRIB" or "ATTDEF" => "text is not engraved; convert it to outlines (explode) in the CAD program",
                "HATCH" or "SOLID" or "TRACE" => "filled areas are not read; use --fill on their outlines",
                "POINT" => "a point has no length",
                "DIMENSION" or "LEADER" or "MLEADER" or "TOLERANCE" => "annotation is not engraved",
                "VIEWPORT" => "viewports are not geometry",
                _ => "not a supported entity type",
            };
            warnings.Skipped(e.Type, e.ShortId, why);
        }

        private static bool InPlane(DxfEntity e, out bool mirror)
        {
            double nx = e.Number(210, 0), ny = e.Number(220, 0), nz = e.Number(230, 1);
            mirror = nz < 0;
            return Math.Abs(nx) < 1e-9 && Math.Abs(ny) < 1e-9 && nz != 0;
        }

        private void Emit(DrawingPath? raw, Affine transform, string layer, DxfEntity e)
        {
            if (raw is not null)
            {
                _curves += raw.Curves.Count;
                if (Paths.Count >= DrawingLimits.MaxPaths)
                {
                    throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxPaths, "paths (entities that draw)", "split the drawing into files");
                }

                if (_curves > DrawingLimits.MaxCurves)
                {
                    throw DrawingLimits.Exceeded(path, null, DrawingLimits.MaxCurves, "segments and curves", "simplify the drawing");
                }

                Paths.Add(raw.Transform(transform) with { Layer = layer, Source = e.Id });
            }
        }

        private void Insert(DxfEntity e, Affine transform, string layer, int depth)
        {
            var name = e.Text(2) ?? throw e.Error("names no block (group code 2)");
            if (!file.Blocks.TryGetValue(name, out var block))
            {
                throw e.Error($"refers to block \"{name}\", which the file does not define");
            }

            if (depth >= MaxBlockDepth)
            {
                throw e.Error($"blocks nested more than {MaxBlockDepth} deep (does block \"{name}\" insert itself?)");
            }

            double sx = e.Number(41, 1), sy = e.Number(42, 1), rotation = e.Number(50, 0);
            if (sx == 0 || sy == 0)
            {
                throw e.Error($"scale {sx} x {sy} flattens the block \"{name}\" to nothing");
            }

            int columns = Math.Max(1, e.Integer(70, 1)), rows = Math.Max(1, e.Integer(71, 1));
            if ((long)columns * rows > DrawingLimits.MaxExpandedEntities)
            {
                throw DrawingLimits.Exceeded(path, $"INSERT ({e.ShortId}) arrays block \"{name}\" {columns} x {rows} times", DrawingLimits.MaxExpandedEntities, "entities", "make the array smaller");
            }

            double columnSpacing = e.Number(44, 0), rowSpacing = e.Number(45, 0);
            var at = new DrawingPoint(e.Number(10, 0), e.Number(20, 0));
            for (var r = 0; r < rows; r++)
            {
                for (var c = 0; c < columns; c++)
                {
                    var m = Affine.Translate(-block.BasePoint.X, -block.BasePoint.Y);
                    m = Affine.Compose(m, Affine.Scale(sx, sy));
                    m = Affine.Compose(m, Affine.Translate(c * columnSpacing, r * rowSpacing));
                    m = Affine.Compose(m, Affine.Rotate(rotation));
                    m = Affine.Compose(m, Affine.Translate(at.X, at.Y));
                    m = Affine.Compose(m, transform);
                    foreach (var child in block.Entities)
                    {
                        Convert(child, m, layer, depth + 1);
                    }
                }
            }
        }

        private DrawingPath? Build(DxfEntity e)
        {
            switch (e.Type)
            {
                case "LINE":
                    var line = new LineCurve(new(e.Number(10, 0), e.Number(20, 0)), new(e.Number(11, 0), e.Number(21, 0)));
                    return new DrawingPath([line], false, string.Empty, string.Empty);
                case "CIRCLE":
                    var radius = Radius(e);
                    return new DrawingPath([EllipticalArcCurve.Circular(new(e.Number(10, 0), e.Number(20, 0)), radius, 0, 360)], true, string.Empty, string.Empty);
                case "ARC":
                    double start = e.Number(50, 0), end = e.Number(51, 0);
                    var sweep = (((end - start) % 360) + 360) % 360;
                    var arc = EllipticalArcCurve.Circular(new(e.Number(10, 0), e.Number(20, 0)), Radius(e), start, sweep == 0 ? 360 : sweep);
                    return new DrawingPath([arc], sweep == 0, string.Empty, string.Empty);
                case "ELLIPSE":
                    return Ellipse(e);
                case "SPLINE":
                    return Spline(e);
                case "LWPOLYLINE":
                    return LightweightPolyline(e);
                default:
                    return Polyline(e);
            }
        }

        private static double Radius(DxfEntity e)
        {
            var radius = e.Number(40);
            return radius > 0 ? radius : throw e.Error($"radius {radius.ToString(CultureInfo.InvariantCulture)} must be above 0");
        }

        private static DrawingPath Ellipse(DxfEntity e)
        {
            var center = new DrawingPoint(e.Number(10, 0), e.Number(20, 0));
            var major = new DrawingPoint(e.Number(11), e.Number(21));
            var ratio = e.Number(40, 1);
            if (major.Length == 0 || !(ratio > 0) || ratio > 1.000001)
            {
                throw e.Error($"major axis {major.Length.ToString(CultureInfo.InvariantCulture)} and axis ratio {ratio.ToString(CultureInfo.InvariantCulture)} make no ellipse");
            }

            // The minor axis is the extrusion direction crossed with the major axis.
            var nz = e.Number(230, 1) < 0 ? -1 : 1;
            var minor = new DrawingPoint(-nz * major.Y * ratio, nz * major.X * ratio);
            double start = e.Number(41, 0), end = e.Number(42, 2 * Math.PI);
            var sweep = ((end - start) % (2 * Math.PI) + (2 * Math.PI)) % (2 * Math.PI);
            var full = sweep < 1e-12 || Math.Abs(sweep - (2 * Math.PI)) < 1e-12;
            return new DrawingPath([new EllipticalArcCurve(center, major, minor, start, full ? 2 * Math.PI : sweep)], full, string.Empty, string.Empty);
        }

        private DrawingPath? Spline(DxfEntity e)
        {
            var degree = e.Integer(71, 3);
            var xs = e.Numbers(10);
            var ys = e.Numbers(20);
            if (xs.Count == 0)
            {
                warnings.Skipped("SPLINE", e.ShortId, "defined by fit points only (no control points); save it with control points or as a polyline");
                return null;
            }

            if (xs.Count != ys.Count)
            {
                throw e.Error($"{xs.Count} control point x values but {ys.Count} y values");
            }

            var knots = e.Numbers(40);
            var weights = e.Numbers(41);
            var flags = e.Integer(70, 0);
            try
            {
                var curve = new NurbsCurve(
                    degree,
                    [.. knots],
                    [.. xs.Zip(ys, (x, y) => new DrawingPoint(x, y))],
                    weights.Count == 0 || weights.All(w => w == 1) ? null : [.. weights]);
                var closed = (flags & 1) != 0 || curve.Start == curve.End;
                return new DrawingPath([curve], closed, string.Empty, string.Empty);
            }
            catch (ArgumentException ex)
            {
                throw e.Error(ex.Message.Split(" (Parameter", 2)[0]);
            }
        }

        private static DrawingPath? LightweightPolyline(DxfEntity e)
        {
            var vertices = new List<(DrawingPoint Point, double Bulge)>();
            double? x = null;
            foreach (var (code, value, line) in e.Groups)
            {
                switch (code)
                {
                    case 10:
                        x = e.Parse(value, line);
                        break;
                    case 20 when x is { } vx:
                        vertices.Add((new DrawingPoint(vx, e.Parse(value, line)), 0));
                        x = null;
                        break;
                    case 42 when vertices.Count > 0:
                        vertices[^1] = (vertices[^1].Point, e.Parse(value, line));
                        break;
                }
            }

            return Vertices(e, vertices, (e.Integer(70, 0) & 1) != 0);
        }

        private DrawingPath? Polyline(DxfEntity e)
        {
            var flags = e.Integer(70, 0);
            if ((flags & (16 | 64)) != 0)
            {
                warnings.Skipped("POLYLINE", e.ShortId, "polygon and polyface meshes are 3D surfaces, not paths");
                return null;
            }

            // Spline-fitted polylines keep their frame (flag 16) beside the fitted vertices: only the latter are the path.
            var vertices = e.Children
                .Where(v => (v.Integer(70, 0) & 16) == 0)
                .Select(v => (new DrawingPoint(v.Number(10, 0), v.Number(20, 0)), v.Number(42, 0)))
                .ToList();
            return Vertices(e, vertices, (flags & 1) != 0);
        }

        private static DrawingPath? Vertices(DxfEntity e, List<(DrawingPoint Point, double Bulge)> vertices, bool closed)
        {
            if (vertices.Count < 2)
            {
                throw e.Error($"{vertices.Count} vertex: a polyline needs at least 2");
            }

            var curves = new List<IDrawingCurve>();
            var segments = closed ? vertices.Count : vertices.Count - 1;
            for (var i = 0; i < segments; i++)
            {
                var (p0, bulge) = vertices[i];
                var p1 = vertices[(i + 1) % vertices.Count].Point;
                if (p0 == p1)
                {
                    continue;
                }

                curves.Add(bulge == 0 ? new LineCurve(p0, p1) : Bulge(p0, p1, bulge));
            }

            if (curves.Count == 0)
            {
                throw e.Error("every vertex is at the same point: the polyline has no length");
            }

            return new DrawingPath(curves, closed || curves[0].Start == curves[^1].End, string.Empty, string.Empty);
        }

        /// <summary>The arc from p0 to p1 whose bulge b is the tangent of a quarter of its included angle (positive = counter-clockwise).</summary>
        private static EllipticalArcCurve Bulge(DrawingPoint p0, DrawingPoint p1, double bulge)
        {
            var chord = p1 - p0;
            var d = chord.Length;
            var sweep = 4 * Math.Atan(bulge);
            var left = new DrawingPoint(-chord.Y / d, chord.X / d);
            var center = ((p0 + p1) * 0.5) + (left * (d / 2 * (1 - (bulge * bulge)) / (2 * bulge)));
            var radius = d / (2 * Math.Abs(Math.Sin(sweep / 2)));
            var startAngle = Math.Atan2(p0.Y - center.Y, p0.X - center.X);
            return new EllipticalArcCurve(center, new(radius, 0), new(0, radius), startAngle, sweep, p0, p1);
        }
    }
}
