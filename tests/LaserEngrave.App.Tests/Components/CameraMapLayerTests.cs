using Bunit;
using LaserEngrave.App.Components.Workspace;
using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Camera;
using LaserEngrave.Core.Geometry;
using NSubstitute;

namespace LaserEngrave.App.Tests.Components;

/// <summary>The camera's stitched map drawn under the stage canvas, where on the stage it was taken (issue 37).</summary>
public sealed class CameraMapLayerTests : ComponentTest
{
    [Fact]
    public async Task ScanMap_Done_StageCanvasDrawsTheMapAtItsStageRectangle()
    {
        var service = Substitute.For<ICameraService>();
        service.Camera.Returns(new CameraProfile { WidthPx = 320, HeightPx = 240, UmPerPixel = 2 });
        service.IsTwin.Returns(true);
        service.CanMove.Returns(true);
        service.StagePositionUm.Returns((10_000.0, 20_000.0));
        // A 1 x 1 mm map at 4 µm a pixel: 251 pixels a side, pixel (0, 0) centred at (9500, 19500) µm.
        var map = new SampleMap(new CameraFrame(251, 251, new byte[251 * 251]), 9_500, 19_500, 4, [], []);
        service.ScanMapAsync(9_500, 19_500, 1_000, 1_000, Arg.Any<CancellationToken>()).Returns(map);
        var camera = new CameraViewModel(service);
        // The canvas' module and its view object (what create returns), so the calls made on the view are recorded.
        var module = JSInterop.SetupModule("./Components/Workspace/StageCanvas.razor.js");
        module.Mode = JSRuntimeMode.Loose;
        var view = module.SetupModule(i => i.Identifier == "create");
        view.Mode = JSRuntimeMode.Loose;
        var cut = Render<StageCanvas>(p => p.Add(c => c.Job, Main.Job).Add(c => c.Machine, Main.Machine).Add(c => c.Moves, Main.TestMoves).Add(c => c.Run, Main.Run).Add(c => c.Camera, camera));

        await cut.InvokeAsync(() => camera.ScanMapCommand.ExecuteAsync(null));

        // Its edge half a map pixel before the first pixel's centre; 251 pixels of 4 µm.
        cut.WaitForAssertion(() =>
        {
            var call = view.Invocations.Last(i => i.Identifier == "setMap");
            Assert.StartsWith("data:image/png;base64,", (string)call.Arguments[0]!, StringComparison.Ordinal);
            Assert.Equal(9.498, (double)call.Arguments[1]!, 6);
            Assert.Equal(19.498, (double)call.Arguments[2]!, 6);
            Assert.Equal(1.004, (double)call.Arguments[3]!, 6);
            Assert.Equal(1.004, (double)call.Arguments[4]!, 6);
        });
        Assert.Equal("Map: 0 frames, worst seam 0 camera px over 0 seams; 251 x 251 px at 4 µm a pixel", camera.MapText);
    }
}
