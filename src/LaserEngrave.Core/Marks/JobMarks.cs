using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// What a job file's marks are numbered and drawn with when the file is read: the sample counter, the machine (its spot
/// and its name), the time for {date} and {time} and the run's sample ID. A resumed run gives the first number and the
/// time its log carries, so it burns the same numbers and the same texts it started with.
/// </summary>
/// <param name="CounterPath">The sample counter: the next number comes from it, and a completed run advances it.</param>
/// <param name="Profile">The machine: codes are drawn at a pitch its spot fills; {profile} is its name.</param>
/// <param name="Now">When the marks are made, for {date} and {time}.</param>
/// <param name="Sample">The run's sample ID, for {sample}; null refuses a mark that asks for it.</param>
public sealed record JobMarks(string CounterPath, MachineProfile Profile, DateTimeOffset Now, string? Sample)
{
    /// <summary>The first number to use instead of the counter's next (a resumed run's, from its log); null: the counter's.</summary>
    public int? FirstNumber { get; init; }
}
