using System.Globalization;

namespace LaserEngrave.Core.Sweeps;

/// <summary>One parameter and its values, one value a row (or a column) of the grid, in the order given.</summary>
public sealed record SweepAxis(SweepParameter Parameter, IReadOnlyList<double> Values)
{
    /// <summary>The most values along one axis.</summary>
    public const int MaxValues = 50;

    /// <summary>Parses <c>name=v1,v2,...</c> (e.g. <c>speed=0.5,1,2</c>); throws <see cref="SweepException"/> naming <paramref name="option"/>.</summary>
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

        var values = new List<double>();
        foreach (var part in text[(equals + 1)..].Split(','))
        {
            if (!double.TryParse(part, NumberStyles.Float, CultureInfo.InvariantCulture, out var value) || !double.IsFinite(value))
            {
                throw new SweepException($"{option} {text}: '{part}' is not a number");
            }

            if (parameter.IsWhole() && value != Math.Round(value))
            {
                throw new SweepException($"{option} {text}: {parameter.CliName()} takes whole numbers, not {part}");
            }

            values.Add(value);
        }

        if (values.Count > MaxValues)
        {
            throw new SweepException($"{option} {text}: {values.Count} values, at most {MaxValues}");
        }

        return new SweepAxis(parameter, values);
    }

    /// <summary>The axis as the command line gives it: <c>speed=0.5,1,2</c>.</summary>
    public override string ToString() =>
        Parameter.CliName() + "=" + string.Join(',', Values.Select(v => v.ToString("0.######", CultureInfo.InvariantCulture)));
}
