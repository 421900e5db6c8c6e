using System.Globalization;

namespace LaserEngrave.Core.Sweeps;

/// <summary>One parameter and its values, one value a row (or a column) of the grid, in the order given.</summary>
public sealed record SweepAxis(SweepParameter Parameter, IReadOnlyList<double> Values)
{
    /// <summary>The most values along one axis.</summary>
    public const int MaxValues = 50;

    /// <summary>Parses <c>name=v1,v2,...</c> (e.g. <c>speed=0.5,1,2</c>, or <c>speed=0,5;1;2</c> with decimal commas) or <c>name=from..to:step</c> (e.g. <c>focus=-200..200:50</c>); throws <see cref="SweepException"/> naming <paramref name="option"/>.</summary>
    public static SweepAxis Parse(string text, string option)
    {
        ArgumentNullException.ThrowIfNull(text);
        var equals = text.IndexOf('=', StringComparison.Ordinal);
        if (equals <= 0)
        {
            throw new SweepException($"{option} {text}: expected PARAMETER=V1,V2,..., e.g. speed=0.5,1,2");
        }

        SweepParameter parameter;
        try
        {
            parameter = SweepParameters.Parse(text[..equals]);
        }
        catch (SweepException ex)
        {
            throw new SweepException($"{option} {text}: {ex.Message}", ex);
        }

        return Parse(parameter, text[(equals + 1)..], $"{option} {text}");
    }

    /// <summary>The values of <paramref name="parameter"/> from <c>v1,v2,...</c> or <c>from..to:step</c>; <paramref name="where"/> begins every error line (the option and what it was given).</summary>
    public static SweepAxis Parse(SweepParameter parameter, string list, string where)
    {
        ArgumentNullException.ThrowIfNull(list);
        var values = new List<double>();
        foreach (var value in list.Contains("..", StringComparison.Ordinal) ? Range(list, where) : Input.NumberText.SplitList(list).Select(part => Number(part, where)))
        {
            if (parameter.IsWhole() && value != Math.Round(value))
            {
                throw new SweepException($"{where}: {parameter.CliName()} takes whole numbers, not {value.ToString(CultureInfo.InvariantCulture)}");
            }

            values.Add(value);
        }

        if (values.Count > MaxValues)
        {
            throw new SweepException($"{where}: {values.Count} values, at most {MaxValues}");
        }

        return new SweepAxis(parameter, values);
    }

    private static double Number(string part, string where) =>
        Input.NumberText.TryParse(part, out var value, out var problem)
            ? value
            : throw new SweepException($"{where}: '{part.Trim()}' {problem}");

    // from..to:step, from and to both included; each value from + i step computed from the start, so no sum drifts.
    private static IEnumerable<double> Range(string list, string where)
    {
        var colon = list.IndexOf(':', StringComparison.Ordinal);
        var dots = list.IndexOf("..", StringComparison.Ordinal);
        if (colon < dots)
        {
            throw new SweepException($"{where}: expected FROM..TO:STEP, e.g. focus=-200..200:50");
        }

        var from = Number(list[..dots], where);
        var to = Number(list[(dots + 2)..colon], where);
        var step = Number(list[(colon + 1)..], where);
        if (!(step > 0))
        {
            throw new SweepException($"{where}: the step must be above 0");
        }

        var count = Math.Floor((Math.Abs(to - from) / step) + 1e-9) + 1;
        if (count > MaxValues)
        {
            throw new SweepException($"{where}: {count} values, at most {MaxValues}");
        }

        var sign = to >= from ? 1 : -1;
        return Enumerable.Range(0, (int)count).Select(i => from + (sign * i * step));
    }

    /// <summary>The axis as the command line gives it: <c>speed=0.5,1,2</c>.</summary>
    public override string ToString() =>
        Parameter.CliName() + "=" + string.Join(',', Values.Select(v => v.ToString("0.######", CultureInfo.InvariantCulture)));
}
