using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Jobs;

/// <summary>A job value the rules refuse: which field (a <see cref="JobField"/> name), the value given and the rule it breaks.</summary>
/// <param name="Field">The field, one of <see cref="JobField"/>'s names.</param>
/// <param name="Value">The value as given.</param>
/// <param name="Rule">What it must be, in the user's words, e.g. "outside what the stage takes, 0.00093..4 mm/s (the profile's maxSpeedMmPerS)".</param>
public sealed record FieldProblem(string Field, double Value, string Rule)
{
    /// <summary>The value as messages show it: invariant, short, in exponent form when huge or tiny.</summary>
    public string ValueText => MachineLimits.Text.N(Value);

    /// <summary>One line in the app's words: "burn speed 5 mm/s: outside what the stage takes, ...".</summary>
    public string Message => $"{JobField.Label(Field)} {ValueText}{JobField.Unit(Field)}: {Rule}";

    /// <summary>One line naming the value by <paramref name="name"/> (an option, a file's field): "--speed-mm-s 5: outside ...".</summary>
    public string MessageFor(string name) => $"{name} {ValueText}: {Rule}";
}
