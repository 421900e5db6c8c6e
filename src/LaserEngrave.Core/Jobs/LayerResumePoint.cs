using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>Where a run of layers that did not complete goes on: the layer, its passes already done, and where its next pass stopped.</summary>
/// <param name="Layer">The first layer not completed, from 0; the layers before it completed and are not burned again.</param>
/// <param name="PassesDone">Its passes completed before the stop.</param>
/// <param name="StopPoint">Where its pass under way stopped (a raster row and move, or a drawing's stroke): that pass goes on from there; null starts that pass over.</param>
public sealed record LayerResumePoint(int Layer, int PassesDone, RunStopPoint? StopPoint);
