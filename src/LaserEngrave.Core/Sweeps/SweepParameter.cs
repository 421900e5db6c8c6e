namespace LaserEngrave.Core.Sweeps;

/// <summary>A process value a sweep varies over its rows or columns.</summary>
public enum SweepParameter
{
    /// <summary>Burn speed, mm/s.</summary>
    Speed,

    /// <summary>Laser (Q-switch) frequency, Hz.</summary>
    Frequency,

    /// <summary>Passes over the same cell, 1..100.</summary>
    Passes,

    /// <summary>Pulses at each dot (dot mode only).</summary>
    PulsesPerDot,

    /// <summary>The cell's pixel pitch, µm: the distance between raster lines, lines of a line set and dots of a dot array.</summary>
    Pitch,

    /// <summary>The focus, µm from the profile's visible focus (z.focusMm): moves the Z axis before the cell (machines with a Z axis only).</summary>
    Focus,
}

/// <summary>Names and units of the sweep parameters, as the command line, the log and the labels say them.</summary>
public static class SweepParameters
{
    /// <summary>The name on the command line (<c>--rows speed=...</c>).</summary>
    public static string CliName(this SweepParameter parameter) => parameter switch
    {
        SweepParameter.Speed => "speed",
        SweepParameter.Frequency => "frequency",
        SweepParameter.Passes => "passes",
        SweepParameter.PulsesPerDot => "pulses-per-dot",
        SweepParameter.Pitch => "pitch",
        SweepParameter.Focus => "focus",
        _ => throw new ArgumentOutOfRangeException(nameof(parameter)),
    };

    /// <summary>The key in the sweep log's cell parameters, with its unit.</summary>
    public static string LogKey(this SweepParameter parameter) => parameter switch
    {
        SweepParameter.Speed => "speedMmPerS",
        SweepParameter.Frequency => "frequencyHz",
        SweepParameter.Passes => "passes",
        SweepParameter.PulsesPerDot => "pulsesPerDot",
        SweepParameter.Pitch => "pitchUm",
        SweepParameter.Focus => "focusUm",
        _ => throw new ArgumentOutOfRangeException(nameof(parameter)),
    };

    public static string Unit(this SweepParameter parameter) => parameter switch
    {
        SweepParameter.Speed => "mm/s",
        SweepParameter.Frequency => "Hz",
        SweepParameter.Pitch or SweepParameter.Focus => "µm",
        _ => string.Empty,
    };

    /// <summary>The parameter a log key names (<see cref="LogKey"/>); null for a key this version does not know.</summary>
    public static SweepParameter? FromLogKey(string key) =>
        Enum.GetValues<SweepParameter>().Select(p => (SweepParameter?)p).FirstOrDefault(p => p!.Value.LogKey() == key);

    /// <summary>
    /// A cell's values as the screen says them, e.g. "speed 0.5 mm/s, frequency 500 Hz" (the log's keys, such as
    /// <c>speedMmPerS</c>, are for files, not for people).
    /// </summary>
    public static string Describe(IEnumerable<KeyValuePair<string, double>> parameters) =>
        string.Join(", ", parameters.Select(p => FromLogKey(p.Key) is { } known
            ? string.Create(System.Globalization.CultureInfo.InvariantCulture, $"{known.CliName().Replace('-', ' ')} {p.Value:0.######}{(known.Unit().Length > 0 ? " " + known.Unit() : string.Empty)}")
            : string.Create(System.Globalization.CultureInfo.InvariantCulture, $"{p.Key} {p.Value:0.######}")));

    /// <summary>
    /// A cell's values as its label on the stage says them, each with its unit and nothing else: "1.6 mm/s · 1000 Hz",
    /// "2 passes", "3 pulses", "50 µm".
    /// </summary>
    public static string Label(IEnumerable<KeyValuePair<string, double>> parameters) =>
        string.Join(" · ", parameters.Select(p =>
        {
            var value = p.Value.ToString("0.###", System.Globalization.CultureInfo.InvariantCulture);
            return FromLogKey(p.Key) switch
            {
                SweepParameter.Passes => p.Value == 1 ? "1 pass" : $"{value} passes",
                SweepParameter.PulsesPerDot => p.Value == 1 ? "1 pulse" : $"{value} pulses",
                { } known when known.Unit().Length > 0 => $"{value} {known.Unit()}",
                _ => value,
            };
        }));

    /// <summary>Whether the value must be a whole number.</summary>
    public static bool IsWhole(this SweepParameter parameter) => parameter is SweepParameter.Passes or SweepParameter.PulsesPerDot;

    public static SweepParameter Parse(string text) => text.Trim().ToLowerInvariant() switch
    {
        "speed" => SweepParameter.Speed,
        "frequency" or "freq" => SweepParameter.Frequency,
        "passes" => SweepParameter.Passes,
        "pulses-per-dot" or "pulses" => SweepParameter.PulsesPerDot,
        "pitch" => SweepParameter.Pitch,
        "focus" => SweepParameter.Focus,
        _ => throw new SweepException($"'{text}' is not a sweep parameter: use speed, frequency, passes, pulses-per-dot, pitch or focus"),
    };
}
