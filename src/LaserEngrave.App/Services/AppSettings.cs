using LaserEngrave.Core.Jobs;
namespace LaserEngrave.App.Services;

/// <summary>What the app keeps between starts.</summary>
public sealed record AppSettings
{
    public string? LastFolder { get; init; }

    /// <summary>Most recent first.</summary>
    public IReadOnlyList<string> RecentFiles { get; init; } = [];

    public bool UseSimulator { get; init; } = true;

    public string? StagePort { get; init; }

    public string? LaserPort { get; init; }

    /// <summary>A machine profile JSON file; null for the built-in profile.</summary>
    public string? ProfilePath { get; init; }

    /// <summary>The last job's size, position and process (its image is the first recent file), restored at the next start.</summary>
    public JobSettings? LastJob { get; init; }

    /// <summary>"system" (the system's light or dark mode), "light" or "dark": the page's colours and Fluent UI's.</summary>
    public string Theme { get; init; } = "system";

    /// <summary>
    /// True once the user writes decimals with a comma ("20,5"): the number fields then show theirs with a comma too,
    /// never rewriting what was typed. A number typed with a point sets it back.
    /// </summary>
    public bool DecimalComma { get; init; }

    /// <summary>A run estimated longer than this, minutes, asks before it starts (Start and the API's 409); an hour until set.</summary>
    public double AskAboveMinutes { get; init; } = 60;
}
