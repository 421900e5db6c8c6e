using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;

namespace LaserEngrave.Machines.Marks;

/// <summary>What a front end asks <see cref="MarkMaking"/> to make.</summary>
/// <param name="Spec">The mark, its copies and its process.</param>
/// <param name="Counter">The sample counter the copies are numbered from and the job advances.</param>
/// <param name="Context">The sample, the time and the profile's name for the placeholders.</param>
/// <param name="Machine">The machine profile in force (its spot, process and travel).</param>
/// <param name="Folder">The folder the job and each mark's files are written to.</param>
public sealed record MarkOrder(MarkSpec Spec, MarkCounter Counter, MarkContext Context, MachineProfile Machine, string Folder)
{
    /// <summary>Numbers from this one on (a new batch) instead of the counter's next; written to the counter with the job.</summary>
    public int? StartAt { get; init; }

    /// <summary>How the front end names a marks file's field (see <see cref="MarkLayout.Make"/>); null keeps the file's names.</summary>
    public Func<string, string>? Name { get; init; }

    /// <summary>Burn every code on the twin and read it back; the job is saved only when all read.</summary>
    public bool Check { get; init; }

    /// <summary>With <see cref="Check"/>: also find the smallest module of the first code that still reads.</summary>
    public bool Smallest { get; init; }
}
