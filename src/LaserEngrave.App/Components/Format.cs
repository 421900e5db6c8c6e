using System.Globalization;
using LaserEngrave.Core.Geometry;

namespace LaserEngrave.App.Components;

/// <summary>Numbers as the views show them.</summary>
public static class Format
{
    /// <summary>"42 s", "3 min 05 s", "2 h 07 min".</summary>
    public static string Duration(double seconds)
    {
        if (!double.IsFinite(seconds) || seconds < 0)
        {
            return "–";
        }

        var t = TimeSpan.FromSeconds(Math.Round(seconds));
        return t.TotalHours >= 1 ? string.Create(CultureInfo.InvariantCulture, $"{(int)t.TotalHours} h {t.Minutes:00} min")
            : t.TotalMinutes >= 1 ? string.Create(CultureInfo.InvariantCulture, $"{t.Minutes} min {t.Seconds:00} s")
            : string.Create(CultureInfo.InvariantCulture, $"{t.Seconds} s");
    }

    /// <summary>A stage position in mm from microsteps.</summary>
    public static string Mm(long? microsteps, double microstepUm) =>
        microsteps is { } m ? StageUnits.MicrostepsToMm(m, microstepUm).ToString("0.000", CultureInfo.InvariantCulture) : "–";

    /// <summary>
    /// A count with its thousands grouped by a narrow space ("2 464"), as SI writes them: a comma or a point there would
    /// read as a decimal mark to half the labs.
    /// </summary>
    public static string Count(long count) =>
        count.ToString("#,0", Grouping);

    private static readonly NumberFormatInfo Grouping = new() { NumberGroupSeparator = "\u202F", NumberDecimalSeparator = "." };

    /// <summary>
    /// A button's tooltip, which Fluent UI's button also makes its accessible name: its visible label first ("Frame: trace
    /// the job's outline, laser off"), so a screen reader reads, and voice control finds, the word the button shows.
    /// </summary>
    public static string Named(string label, string what) => $"{label}: {what}";
}
