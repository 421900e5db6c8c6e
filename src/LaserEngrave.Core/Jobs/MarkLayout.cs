using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Jobs;

/// <summary>
/// Marks made into a job of layers: each copy's code as an image layer (a 1-bit BMP at a pitch the spot fills) and its
/// text as a drawing layer (the engraving font's strokes as an SVG) or an image layer (a system font), written into one
/// folder with the job file, so the run engine burns them as any other job. The layers' names carry the resolved
/// texts, so the run log records every mark's text and where it was burned.
/// </summary>
public sealed class MarkLayout
{
    private MarkLayout(MarkSpec spec, int first, IReadOnlyList<PlacedMark> marks, IReadOnlyList<JobLayer> layers, IReadOnlyList<CodeRaster> codes)
    {
        Spec = spec;
        FirstNumber = first;
        Marks = marks;
        Layers = layers;
        Codes = codes;
    }

    public MarkSpec Spec { get; }

    /// <summary>The first copy's number.</summary>
    public int FirstNumber { get; }

    /// <summary>Every copy in burn order, with its code and its text when the mark has both.</summary>
    public IReadOnlyList<PlacedMark> Marks { get; }

    /// <summary>The job's layers, sources in the folder.</summary>
    public IReadOnlyList<JobLayer> Layers { get; }

    /// <summary>Each copy's code as drawn (empty for a text alone).</summary>
    public IReadOnlyList<CodeRaster> Codes { get; }

    /// <summary>How a code's image file ends (mark-001-code.bmp).</summary>
    public const string CodeFileSuffix = "-code.bmp";

    /// <summary>The job file's name in the folder.</summary>
    public const string JobFileName = "job.json";

    /// <summary>The marks' record beside the job file: the counter, the first number, and each mark.</summary>
    public const string ManifestFileName = MarkManifest.FileName;

    /// <summary>Checks <paramref name="spec"/>, resolves every copy's text and draws its code and text into <paramref name="folder"/>.</summary>
    /// <param name="first">The first copy's number (the counter's next).</param>
    /// <param name="context">The run's sample, the time and the profile (its number is set per copy).</param>
    /// <param name="name">
    /// How the front end names a marks file's field (<c>originMm</c> as <c>--origin-mm</c> on the command line, "origin" in
    /// the app), so a refusal says what the user gave and what to change; null keeps the marks file's names.
    /// </param>
    /// <exception cref="MarkException">A value is out of range, a text does not fit, a module is smaller than the spot, or a copy lies off the travel.</exception>
    public static MarkLayout Make(MarkSpec spec, int first, MarkContext context, MachineProfile profile, string folder, Func<string, string>? name = null)
    {
        ArgumentNullException.ThrowIfNull(spec);
        ArgumentNullException.ThrowIfNull(context);
        ArgumentNullException.ThrowIfNull(profile);
        name ??= field => field;
        Check(spec, first, profile, name);

        // Every copy is drawn before a file is written: a copy whose text does not fit refuses the whole array.
        var copies = Enumerable.Range(0, spec.Copies)
            .Select(i => MarkText.Resolve(spec.Text, context with { Number = first + i }))
            .Select(text => (Text: text, Copy: Draw(spec, text, profile)))
            .ToList();
        CheckTravel(spec, copies.Select(c => (c.Text, c.Copy.WidthMm, c.Copy.HeightMm)).ToList(), first, profile, name);
        try
        {
            Directory.CreateDirectory(folder);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException or ArgumentException or NotSupportedException)
        {
            throw new MarkException($"{folder}: the marks' folder cannot be made there ({ex.Message})", ex);
        }

        // A job made here before is taken away first: if these marks are refused (a code that does not read), no old job stays to be burned by mistake.
        File.Delete(Path.Combine(folder, JobFileName));
        File.Delete(Path.Combine(folder, ManifestFileName));
        var marks = new List<PlacedMark>();
        var layers = new List<JobLayer>();
        var codes = new List<CodeRaster>();
        var columns = ColumnsOf(spec);
        double? pitchX = spec.PitchXMm, pitchY = spec.PitchYMm;
        for (var i = 0; i < spec.Copies; i++)
        {
            var number = first + i;
            var (text, copy) = copies[i];

            // The grid's pitch comes from the first copy unless given: later copies' texts may differ in width.
            pitchX ??= copy.WidthMm + 1;
            pitchY ??= copy.HeightMm + 1;
            var x = spec.Origin.X + ((i % columns) * pitchX.Value);
            var y = spec.Origin.Y + ((i / columns) * pitchY.Value);
            var tag = number.ToString("000", CultureInfo.InvariantCulture);
            if (copy.Code is { } code)
            {
                var source = Path.Combine(folder, $"mark-{tag}{CodeFileSuffix}");
                BmpMaskWriter.Write(source, code.Mask, code.PitchUm);
                var quietMm = Units.StepsToMm(code.QuietModules, code.ModuleUm);
                layers.Add(Layer(spec, $"{KindName(code.Symbol.Kind)} \"{text}\"", source, LayerMode.Raster, code.WidthMm, new OriginMm(x, y)));
                marks.Add(new PlacedMark(number, text, KindKey(code.Symbol.Kind), x + quietMm, y + quietMm, code.SymbolMm, code.SymbolMm, code.ModuleUm));
                codes.Add(code);
            }

            if (copy.Strokes is { } strokes)
            {
                var source = Path.Combine(folder, $"mark-{tag}-text.svg");
                var (inkMin, inkMax) = strokes.InkBounds();
                strokes.WriteSvg(source, -inkMin.X, -inkMin.Y);
                var left = x + copy.TextLeftMm;
                var top = y + copy.TextTopMm;
                layers.Add(Layer(spec, $"text \"{text}\"", source, LayerMode.Outline, null, new OriginMm(left + inkMin.X, top + inkMin.Y)));
                marks.Add(new PlacedMark(number, text, "text", left + inkMin.X, top + inkMin.Y, inkMax.X - inkMin.X, inkMax.Y - inkMin.Y, null));
            }
            else if (copy.Raster is { } raster)
            {
                var source = Path.Combine(folder, $"mark-{tag}-text.bmp");
                var pitchUm = profile.SpotDiameterUm;
                BmpMaskWriter.Write(source, raster, pitchUm);
                var widthMm = Units.StepsToMm(raster.Width, pitchUm);
                var left = x + copy.TextLeftMm;
                var top = y + copy.TextTopMm;
                layers.Add(Layer(spec, $"text \"{text}\"", source, LayerMode.Raster, widthMm, new OriginMm(left, top)));
                marks.Add(new PlacedMark(number, text, "text", left, top, widthMm, Units.StepsToMm(raster.Height, pitchUm), null));
            }
        }

        return new MarkLayout(spec, first, marks, layers, codes);
    }

    /// <summary>Writes the job file and the marks' record into <paramref name="folder"/>.</summary>
    /// <param name="counterPath">The counter a completed run of this job advances.</param>
    /// <returns>The job file's path.</returns>
    public string Save(string folder, string counterPath)
    {
        var job = Path.Combine(folder, JobFileName);
        JobFile.Save(job, Layers);
        MarkManifest.Write(Path.Combine(folder, ManifestFileName), new MarkManifest(Path.GetFullPath(counterPath), FirstNumber, Spec.Copies, Marks));
        return job;
    }

    private static JobLayer Layer(MarkSpec spec, string name, string source, LayerMode mode, double? widthMm, OriginMm origin) => new()
    {
        Name = name,
        Source = source,
        Mode = mode,
        WidthMm = widthMm,
        Origin = origin,
        SpeedMmPerS = spec.SpeedMmPerS,
        FrequencyHz = spec.FrequencyHz,
        Passes = spec.Passes,
    };

    private sealed record Copy(CodeRaster? Code, StrokeText? Strokes, BitMask? Raster, double TextLeftMm, double TextTopMm, double WidthMm, double HeightMm);

    private static Copy Draw(MarkSpec spec, string text, MachineProfile profile)
    {
        CodeRaster? code = null;
        if (spec.Code is { } kind)
        {
            var symbol = CodeSymbol.Encode(kind, text, spec.ErrorCorrection);
            var moduleUm = spec.ModuleUm ?? (Units.MmToUm(spec.SizeMm!.Value) / symbol.Size);
            code = CodeRaster.Render(symbol, moduleUm, spec.Quiet, profile.SpotDiameterUm);
        }

        var codeMm = code?.WidthMm ?? 0;
        var wantText = code is null || spec.Label;
        var textTop = code is null ? 0 : codeMm + spec.GapMm;
        if (!wantText)
        {
            return new Copy(code, null, null, 0, 0, codeMm, codeMm);
        }

        if (spec.Font is { } family)
        {
            var raster = SystemFontText.Render(text, family, spec.TextHeightMm, profile.SpotDiameterUm, spec.Align, spec.LineSpacing);
            var widthMm = Units.StepsToMm(raster.Width, profile.SpotDiameterUm);
            var left = Math.Max(0, (codeMm - widthMm) / 2);
            return new Copy(code, null, raster, left, textTop, Math.Max(codeMm, widthMm), textTop + Units.StepsToMm(raster.Height, profile.SpotDiameterUm));
        }

        var strokes = StrokeText.Layout(text, spec.TextHeightMm, spec.Align, spec.LineSpacing);
        var textLeft = code is null ? 0 : spec.Align switch
        {
            TextAlign.Left => 0,
            TextAlign.Right => codeMm - strokes.WidthMm,
            // Centred by the ink, not the letters' advances: a label looks centred under its code when its strokes are.
            _ => (codeMm - (strokes.InkBounds().Min.X + strokes.InkBounds().Max.X)) / 2,
        };

        // Text wider than the code sticks out to the left when centred or flush right; the copy's box starts at its left.
        var shift = Math.Min(0, textLeft);
        return new Copy(code, strokes, null, textLeft - shift, textTop, Math.Max(codeMm, strokes.WidthMm), textTop + strokes.InkBounds().Max.Y);
    }

    private static void Check(MarkSpec spec, int first, MachineProfile profile, Func<string, string> name)
    {
        if (string.IsNullOrEmpty(spec.Text))
        {
            throw new MarkException("give the mark's text");
        }

        if (spec.Code is not null && (spec.ModuleUm is null) == (spec.SizeMm is null))
        {
            throw new MarkException($"a code needs its module size ({name("moduleUm")}, µm) or its size ({name("sizeMm")}, mm), one of the two");
        }

        if (spec.Code is null && (spec.ModuleUm is not null || spec.SizeMm is not null || spec.ErrorCorrection is not null || spec.QuietModules is not null))
        {
            throw new MarkException($"{name("moduleUm")}, {name("sizeMm")}, {name("quietModules")} and {name("errorCorrection")} are for codes; this mark is a text alone");
        }

        if (spec.SizeMm is { } size && !(size > 0 && size <= 100))
        {
            throw new MarkException(N($"{name("sizeMm")} {size:G6} must be above 0 and at most 100 mm"));
        }

        if (spec.Copies is < 1 or > MarkSpec.MaxCopies)
        {
            throw new MarkException(N($"{name("copies")} {spec.Copies} must be 1..{MarkSpec.MaxCopies}"));
        }

        // More columns than copies is one row of the copies (a panel's Copies lowered below its Columns, a marks file's
        // grid used for one copy): not an error to make the user change a second box for.
        if (spec.Columns is { } columns && (columns < 1 || columns > MarkSpec.MaxCopies))
        {
            throw new MarkException(N($"{name("columns")} {columns} must be 1..{MarkSpec.MaxCopies}"));
        }

        foreach (var (field, value) in new[] { ($"{name("pitchMm")} X", spec.PitchXMm), ($"{name("pitchMm")} Y", spec.PitchYMm) })
        {
            if (value is { } v && !(v > 0 && v <= 1000))
            {
                throw new MarkException(N($"{field} {v:G6} must be above 0 and at most 1000 mm"));
            }
        }

        if (!(spec.GapMm >= 0 && spec.GapMm <= 100))
        {
            throw new MarkException(N($"{name("gapMm")} {spec.GapMm:G6} must be 0..100 mm"));
        }

        if (!(spec.Origin.X >= 0 && spec.Origin.Y >= 0 && double.IsFinite(spec.Origin.X) && double.IsFinite(spec.Origin.Y)))
        {
            throw new MarkException(N($"{name("originMm")} {spec.Origin.X:G6}, {spec.Origin.Y:G6} must not be negative (the stage's travel starts at 0)"));
        }

        // The process's rules, said of the mark (every layer of it has the same) rather than of its first layer.
        var limits = MachineLimits.Of(profile);
        if (spec.SpeedMmPerS is { } speed && JobRules.Speed(speed, limits) is { } speedRule)
        {
            throw new MarkException(N($"{name("speedMmPerS")} {speed:G6}: {speedRule}"));
        }

        if (spec.FrequencyHz is { } hz && JobRules.Frequency(hz, limits) is { } frequencyRule)
        {
            throw new MarkException(N($"{name("frequencyHz")} {hz:G6}: {frequencyRule}"));
        }

        if (JobRules.Passes(spec.Passes) is { } passesRule)
        {
            throw new MarkException(N($"{name("passes")} {spec.Passes}: {passesRule}"));
        }

        if (first < 1 || (long)first + spec.Copies - 1 > MarkCounter.MaxNumber)
        {
            throw new MarkException(N($"numbers {first}..{(long)first + spec.Copies - 1} must lie within 1..{MarkCounter.MaxNumber}"));
        }
    }

    /// <summary>Copies in a row: the spec's columns, at most the copies; all in one row up to ten when it gives none.</summary>
    private static int ColumnsOf(MarkSpec spec) => Math.Min(spec.Columns ?? 10, spec.Copies);

    /// <summary>
    /// Refuses an array whose copies would reach past the stage's travel, before any layer is built, naming the first copy
    /// that would, where it would end, and what to change: the origin, the columns or copies, the pitch.
    /// </summary>
    private static void CheckTravel(MarkSpec spec, IReadOnlyList<(string Text, double WidthMm, double HeightMm)> copies, int first, MachineProfile profile, Func<string, string> name)
    {
        var columns = ColumnsOf(spec);
        var pitchX = spec.PitchXMm ?? copies[0].WidthMm + 1;
        var pitchY = spec.PitchYMm ?? copies[0].HeightMm + 1;
        double travelX = profile.X.TravelMm, travelY = profile.Y.TravelMm;

        if (Largest(copies) is var (w, h) && (w > travelX || h > travelY))
        {
            var (axis, size, travel) = w > travelX ? ("X", w, travelX) : ("Y", h, travelY);
            throw new MarkException($"{(copies.Count == 1 ? "the mark" : "a copy")} is {T(size)} mm in {axis}, more than the stage's travel 0..{T(travel)} mm: make it smaller ({(spec.Code is null ? name("textHeightMm") : $"{name("sizeMm")} or {name("moduleUm")}")})");
        }

        // Copies closer than their own size would burn over each other: a pitch is at least the widest (tallest) copy.
        var rows = ((copies.Count - 1) / columns) + 1;
        var widest = copies.Max(c => c.WidthMm);
        var tallest = copies.Max(c => c.HeightMm);
        if (columns > 1 && pitchX < widest)
        {
            throw new MarkException($"{name("pitchMm")} X {T(pitchX)} mm is less than a copy's width, {T(widest)} mm: the copies would burn over each other");
        }

        if (rows > 1 && pitchY < tallest)
        {
            throw new MarkException($"{name("pitchMm")} Y {T(pitchY)} mm is less than a copy's height, {T(tallest)} mm: the copies would burn over each other");
        }

        // How far past the origin the whole array reaches: the origin may move by the travel less that.
        var spanX = copies.Select((c, i) => ((i % columns) * pitchX) + c.WidthMm).Max();
        var spanY = copies.Select((c, i) => ((i / columns) * pitchY) + c.HeightMm).Max();
        for (var i = 0; i < copies.Count; i++)
        {
            var right = spec.Origin.X + ((i % columns) * pitchX) + copies[i].WidthMm;
            var bottom = spec.Origin.Y + ((i / columns) * pitchY) + copies[i].HeightMm;
            if (right <= travelX && bottom <= travelY)
            {
                continue;
            }

            var (axis, reach, travel, span) = right > travelX ? ("X", right, travelX, spanX) : ("Y", bottom, travelY, spanY);
            var which = copies.Count == 1 ? $"the mark \"{copies[i].Text}\"" : $"copy {i + 1} of {copies.Count} (number {first + i}, \"{copies[i].Text}\")";
            var arrayFix = axis == "X" ? $"fewer {name("columns")} or a smaller {name("pitchMm")}" : $"fewer {name("copies")} (or more {name("columns")}) or a smaller {name("pitchMm")}";
            var fix = span <= travel
                ? $"move {name("originMm")} to at most {T(travel - span)} mm in {axis}{(copies.Count == 1 ? string.Empty : $", or give {arrayFix}")}"
                : $"the array is {T(span)} mm in {axis}, more than the travel: give {arrayFix}";
            throw new MarkException($"{which} would reach {T(reach)} mm in {axis}, past the stage's travel 0..{T(travel)} mm ({name("originMm")} {T(spec.Origin.X)}, {T(spec.Origin.Y)}): {fix}");
        }
    }

    // Millimetres as messages show them: three decimals, in exponent form when huge.
    private static string T(double mm) => Math.Abs(mm) is >= 0.001 and < 1e6 ? mm.ToString("0.###", CultureInfo.InvariantCulture) : MachineLimits.Text.N(mm);

    private static (double WidthMm, double HeightMm) Largest(IReadOnlyList<(string Text, double WidthMm, double HeightMm)> copies) =>
        (copies.Max(c => c.WidthMm), copies.Max(c => c.HeightMm));

    private static string KindName(CodeKind kind) => kind == CodeKind.Qr ? "QR" : "Data Matrix";

    private static string KindKey(CodeKind kind) => kind == CodeKind.Qr ? "qr" : "datamatrix";

    private static string N(FormattableString text) => text.ToString(CultureInfo.InvariantCulture);
}
