using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.App.Services;

/// <summary>Jobs of layers: the JSON files the command line's <c>--job</c> reads, and their plans (docs/vectors.md, "Layers").</summary>
public interface IJobFiles
{
    /// <summary>The layers of a job file.</summary>
    /// <exception cref="Core.Planning.PlanException">Not a job file: one line naming the file, the layer and the field.</exception>
    IReadOnlyList<JobLayer> Load(string path);

    /// <summary>Writes the layers as a job file that <see cref="Load"/> (and the command line) reads back the same.</summary>
    /// <exception cref="IOException">The file cannot be written.</exception>
    void Save(string path, IReadOnlyList<JobLayer> layers);

    /// <summary>Reads, sizes and plans every layer, as <c>engrave --job</c> does.</summary>
    /// <exception cref="Core.Planning.PlanException">One line naming the layer and the problem.</exception>
    LayeredJob Prepare(IReadOnlyList<JobLayer> layers, MachineProfile profile);

    /// <summary>The job files shipped with the app, full paths.</summary>
    IReadOnlyList<string> SampleJobs();

    /// <summary>Where a new job file is offered to be saved.</summary>
    string DefaultFolder { get; }
}
